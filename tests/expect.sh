# expect CODE REGEX COMMAND...: runs COMMAND and fails the test (exit 1,
# its output printed) unless it exits with CODE and a line of its output
# matches REGEX. Sourced by the command's shell tests.
expect() {
  local code=$1 pattern=$2 output status
  shift 2
  set +e
  output=$("$@" 2>&1)
  status=$?
  set -e
  if [ "$status" -ne "$code" ] || ! grep -Eq -- "$pattern" <<<"$output"; then
    printf '%s\n' "$output"
    echo "FAILED: expected exit code $code and /$pattern/, got $status" >&2
    exit 1
  fi
}
