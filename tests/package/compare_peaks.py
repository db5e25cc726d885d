"""Compares `peaks` output (NAME MAX per line, stdin) with a summary.json: equal to the last bit."""
import json
import sys

summary = json.load(open(sys.argv[1]))
lines = [l.split() for l in sys.stdin.read().splitlines() if l.strip()]
assert lines, "the external program printed nothing"
assert [n for n, _ in lines] == list(summary["links"]), (lines, list(summary["links"]))
for name, value in lines:
    assert float(value) == summary["links"][name]["max"], (name, value, summary["links"][name]["max"])
print(f"{len(lines)} link maxima equal to the CLI's")
