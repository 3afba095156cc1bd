#!/usr/bin/env python3
"""The tree's style, held by a baseline that may only shrink (ctest style_format, style_tidy).

  check_style.py format [--update]   clang-format (.clang-format) over every tracked C++ file
  check_style.py tidy [--update]     clang-tidy (.clang-tidy) over penumbra-gen (the whole header library)
                                     and the tools' sources

Each file's count of findings (clang-format: replacements; clang-tidy: warnings per check) is compared
with tests/style/<mode>_baseline.json. A count above the baseline fails and names the file and what to
run; a count below it passes and says the baseline can shrink. --update writes the lower counts into
the baseline and never raises one, so new code is formatted and tidy, and old code only gets better.
Exit 77 (skipped) when the tool is not installed (scripts/setup.sh installs both).
"""
import concurrent.futures
import json
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.realpath(os.path.join(os.path.dirname(__file__), "..", ".."))
TIDY_SOURCES = ["generator/src/main.cpp"]  # the tools' sources are added below
TIDY_FLAGS = ["-std=c++20", "-Iinclude", "-Itools/include", "-Itools/include/penumbra_tools"]


def tracked(*patterns):
    out = subprocess.run(["git", "ls-files", *patterns], cwd=ROOT, capture_output=True, text=True, check=True)
    return sorted(line for line in out.stdout.splitlines() if line)


def format_counts(tool):
    def one(path):
        run = subprocess.run([tool, "--dry-run", path], cwd=ROOT, capture_output=True, text=True)
        return path, {"replacements": run.stderr.count("warning: code should be clang-formatted")}
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 2) as pool:
        return {path: c for path, c in pool.map(one, tracked("*.hpp", "*.cpp", "*.h")) if c["replacements"]}


WARNING = re.compile(r"^(/[^:]+):\d+:\d+: warning: .* \[([\w.-]+)\]$")


def tidy_counts(tool):
    sources = TIDY_SOURCES + tracked("tools/src/*.cpp")

    def one(source):
        run = subprocess.run([tool, "--quiet", source, "--", *TIDY_FLAGS], cwd=ROOT, capture_output=True, text=True)
        if run.returncode != 0 and "error:" in run.stdout + run.stderr:
            sys.exit(f"error: clang-tidy could not read {source}:\n{run.stdout}{run.stderr}")
        return run.stdout

    counts, seen = {}, set()
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 2) as pool:
        for text in pool.map(one, sources):
            for line in text.splitlines():
                m = WARNING.match(line)
                if not m or line in seen:  # a header's finding is reported once per source that includes it
                    continue
                seen.add(line)
                path = os.path.relpath(m.group(1), ROOT)
                counts.setdefault(path, {}).setdefault(m.group(2), 0)
                counts[path][m.group(2)] += 1
    return counts


def main():
    args = sys.argv[1:]
    if not args or args[0] not in ("format", "tidy") or args[1:] not in ([], ["--update"]):
        sys.exit("usage: check_style.py format|tidy [--update]")
    mode, update = args[0], args[1:] == ["--update"]
    tool = shutil.which("clang-format" if mode == "format" else "clang-tidy")
    if not tool:
        print(f"skipped: clang-{mode} is not installed (scripts/setup.sh installs it)")
        return 77
    counts = format_counts(tool) if mode == "format" else tidy_counts(tool)
    baseline_path = os.path.join(ROOT, "tests", "style", f"{mode}_baseline.json")
    with open(baseline_path) as f:
        baseline = json.load(f)
    first_recording = update and not baseline
    if first_recording:
        baseline = counts

    worse, better = [], []
    for path in sorted(set(counts) | set(baseline)):
        for kind in sorted(set(counts.get(path, {})) | set(baseline.get(path, {}))):
            now, allowed = counts.get(path, {}).get(kind, 0), baseline.get(path, {}).get(kind, 0)
            if now > allowed:
                worse.append(f"  {path}: {kind} {now} (baseline {allowed})")
            elif now < allowed:
                better.append(f"  {path}: {kind} {now} (baseline {allowed})")
    total = sum(sum(c.values()) for c in counts.values())
    allowed_total = sum(sum(c.values()) for c in baseline.values())
    print(f"clang-{mode}: {total} findings in {len(counts)} files (baseline {allowed_total} in {len(baseline)})")

    if update:
        shrunk = {}
        for path, kinds in baseline.items():
            kept = {k: min(n, counts.get(path, {}).get(k, 0)) for k, n in kinds.items()}
            kept = {k: n for k, n in kept.items() if n}
            if kept:
                shrunk[path] = kept
        with open(baseline_path + ".tmp", "w") as f:
            json.dump(shrunk, f, indent=1, sort_keys=True)
            f.write("\n")
        os.replace(baseline_path + ".tmp", baseline_path)
        print(f"wrote {os.path.relpath(baseline_path, ROOT)}")
    if better and not update:
        print("below the baseline (run `tests/style/check_style.py " + mode + " --update` to shrink it):")
        print("\n".join(better))
    if worse:
        fix = "git clang-format --extensions hpp,cpp: formats the C++ lines you changed" if mode == "format" else "clang-tidy FILE, then fix what it names"
        print(f"error: above the baseline ({fix}; the baseline only shrinks):")
        print("\n".join(worse))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
