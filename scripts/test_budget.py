#!/usr/bin/env python3
"""Each ctest test's time against its timeout, from the JUnit file of a ctest run.

    scripts/test_budget.py BUILD_DIR JUNIT_XML [--default-timeout S] [--share F]

Prints every test that ran, slowest first, with its time, its timeout (its TIMEOUT property, or
the --default-timeout that scripts/test.sh gives ctest for tests without one) and the share of the
timeout it used. Exits 1 when a test used more than F of its timeout (default 0.5): a test that
passes at 60% of its timeout on one machine times out on a slower one, so it is caught while it
still passes. Exits 2 on bad arguments or unreadable input.
"""
import argparse
import json
import subprocess
import sys
import xml.etree.ElementTree as ElementTree


def timeouts(build_dir):
    """{test name: TIMEOUT property or None} from ctest's own description of the tests."""
    listing = subprocess.run(["ctest", "--test-dir", build_dir, "--show-only=json-v1"],
                             check=True, capture_output=True, text=True).stdout
    result = {}
    for test in json.loads(listing)["tests"]:
        timeout = None
        for prop in test.get("properties", []):
            if prop["name"] == "TIMEOUT":
                timeout = float(prop["value"])
        result[test["name"]] = timeout
    return result


def times(junit_path):
    """[(test name, seconds, status)] of every test case in ctest's JUnit file."""
    root = ElementTree.parse(junit_path).getroot()
    rows = []
    for case in root.iter("testcase"):
        status = case.get("status") or "run"
        if case.find("failure") is not None:
            status = "failed"
        elif case.find("skipped") is not None:
            status = "skipped"
        rows.append((case.get("name"), float(case.get("time") or 0.0), status))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build_dir")
    parser.add_argument("junit_xml")
    parser.add_argument("--default-timeout", type=float, default=None,
                        help="the timeout of tests with no TIMEOUT property (ctest --timeout)")
    parser.add_argument("--share", type=float, default=0.5,
                        help="the largest share of its timeout a test may use (default 0.5)")
    args = parser.parse_args()
    if not 0 < args.share <= 1:
        parser.error(f"--share {args.share}: a share of the timeout must be in (0, 1]")
    try:
        limits = timeouts(args.build_dir)
        rows = times(args.junit_xml)
    except (OSError, subprocess.CalledProcessError, ElementTree.ParseError, json.JSONDecodeError, KeyError) as e:
        print(f"test_budget: cannot read the run: {e}", file=sys.stderr)
        return 2
    if not rows:
        print(f"test_budget: {args.junit_xml} holds no test", file=sys.stderr)
        return 2

    over = []
    print(f"{'test':<52} {'time s':>8} {'timeout s':>10} {'share':>6}  status")
    for name, seconds, status in sorted(rows, key=lambda row: -row[1]):
        limit = limits.get(name) or args.default_timeout
        share = seconds / limit if limit else None
        shown = f"{share:6.0%}" if share is not None else "     -"
        flag = ""
        if share is not None and share > args.share and status != "skipped":
            over.append(name)
            flag = f"  over {args.share:.0%} of its timeout"
        limit_text = f"{limit:10.0f}" if limit else "      none"
        print(f"{name:<52} {seconds:8.1f} {limit_text} {shown}  {status}{flag}")
    total = sum(seconds for _, seconds, _ in rows)
    print(f"{len(rows)} tests, {total:.0f} s of test time")
    if over:
        print(f"test_budget: {len(over)} test(s) used more than {args.share:.0%} of their timeout: "
              f"{', '.join(over)}; raise the TIMEOUT where the time is expected, or make the test cheaper",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
