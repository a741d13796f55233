"""Removes wall times from a command's output, so that two runs of the same
build, or builds meant to behave alike, print the same text.

JSON (one object, or one per line): drops every key that names a time
("seconds", "time", "times", "*_seconds", "*_time", "*_ms"). CSV (--csv):
drops the columns whose header names a time. Any other text: replaces
numbers followed by a time unit (s, ms, µs) with <time>, memory figures
and shares of time likewise. Memory keys (rss, mib) go with the times.
"""
import csv
import io
import json
import re
import sys

TIME_KEY = re.compile(r"(^|_)(seconds?|times?|ms|wall|elapsed|rss|mib)($|_)", re.IGNORECASE)
TIME_TEXT = re.compile(r"[0-9.]+(e-?[0-9]+)? ?(s|ms|µs)\b")
# Memory and shares of time vary from run to run like times do.
MEMORY_TEXT = re.compile(r"(peak RSS|RSS) [0-9.]+(e-?[0-9]+)? ?(MiB|MB|KB|GiB)")
SHARE_TEXT = re.compile(r"[0-9.]+(e-?[0-9]+)? % of the ([a-z ]*)time")


def strip_json(value):
    if isinstance(value, dict):
        return {k: strip_json(v) for k, v in value.items() if not TIME_KEY.search(k)}
    if isinstance(value, list):
        return [strip_json(v) for v in value]
    return value


def strip_csv(text):
    lines = text.splitlines()
    comments = [line for line in lines if line.startswith("#")]
    rows = list(csv.reader(line for line in lines if not line.startswith("#")))
    if not rows:
        return text
    keep = [i for i, name in enumerate(rows[0]) if not TIME_KEY.search(name.strip())]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    for row in rows:
        writer.writerow([row[i] for i in keep if i < len(row)])
    return "\n".join(comments + [buffer.getvalue().rstrip("\n")]) + "\n"


def strip_text(text):
    try:
        return json.dumps(strip_json(json.loads(text)), indent=1, sort_keys=True) + "\n"
    except ValueError:
        pass
    out = []
    for line in text.splitlines():
        try:
            out.append(json.dumps(strip_json(json.loads(line)), sort_keys=True))
        except ValueError:
            line = MEMORY_TEXT.sub(r"\1 <memory>", line)
            line = SHARE_TEXT.sub(r"<share> of the \2time", line)
            out.append(TIME_TEXT.sub("<time>", line))
    return "\n".join(out) + ("\n" if out else "")


def main():
    text = sys.stdin.read()
    sys.stdout.write(strip_csv(text) if "--csv" in sys.argv[1:] else strip_text(text))


if __name__ == "__main__":
    main()
