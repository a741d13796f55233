#!/bin/sh
# A sweep stopped by SIGTERM (as `timeout` sends it) or by its own
# --curve-time-limit writes the points it found: the JSON parses, holds
# converged points, is not complete and its stop reason says why; the exit
# status is 1 (not complete), not a death by the signal.
# Usage: stop_signal.sh EQHB PROBLEMS_DIR
set -u
eqhb=$1 problems=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# 15001 grid points of ~30 ms each: far from done when the signal comes.
"$eqhb" sweep "$problems/lap-joint.toml" --from 1450 --to 1600 --step 0.01 --max-points 20000 --json \
  >"$dir/signal.json" 2>"$dir/signal.err" &
pid=$!
sleep 3
kill -TERM $pid
wait $pid
echo $? >"$dir/signal.code"
"$eqhb" sweep "$problems/friction-1d.toml" --curve-time-limit 1e-9 --json >"$dir/limit.json" 2>"$dir/limit.err"
echo $? >"$dir/limit.code"
python3 - "$dir" <<'PY'
import json, sys
d = sys.argv[1]
def check(name, reason, least):
    code = open(f"{d}/{name}.code").read().strip()
    err = open(f"{d}/{name}.err").read()
    assert code == "1", f"{name}: exit {code}, expected 1; stderr: {err[-500:]}"
    run = json.load(open(f"{d}/{name}.json"))
    text = json.dumps(run)
    assert reason in text, f"{name}: no '{reason}' in the stop reason"
    assert '"complete": false' in text, f"{name}: reported complete"
    points = run["curve"]["points"] if "curve" in run else run["points"]
    converged = [p for p in points if p.get("converged", True)]
    assert len(converged) >= least, f"{name}: {len(converged)} converged points kept, expected >= {least}"
    print(f"{name}: exit 1, {len(converged)} points kept, stop reason has '{reason}'")
check("signal", "stopped on request", 1)
check("limit", "--curve-time-limit of 1e-09 s reached", 1)
PY
