#!/usr/bin/env python3
"""check_docs.py — the `docs` test: the README and the guides in docs/ say what runs.

  check_docs.py --root REPO --program NAME=PATH [--program NAME=PATH ...]

1. Links: every relative link of README.md and docs/*.md names a file of the repository, and a
   `#fragment` a heading of that file (GitHub's anchors: lower case, punctuation dropped, spaces as -).
2. Commands: in every code block (fenced, or indented four spaces), each line that runs one of the
   given programs (by its name, `build/…/NAME` or `NAME` alone; a line ending in `\\` continues) uses
   only flags that program's `--help` prints. `--[no-]x` in the text is found as written or as `--x`.

Exit 0 pass, 1 fail, 2 bad arguments.
"""
import argparse
import pathlib
import re
import subprocess
import sys


def anchors(text):
    out = set()
    for line in text.split("\n"):
        m = re.match(r"^(#{1,6}) +(.*?) *$", line)
        if not m:
            continue
        title = re.sub(r"[`*_]", "", m.group(2)).strip().lower()
        slug = re.sub(r"[^\w\- ]", "", title).replace(" ", "-")
        out.add(slug)
    return out


def code_lines(text):
    """The lines of the code blocks: fenced ones, and those indented four spaces after a blank line."""
    lines, fenced, indented, previous_blank = [], False, False, True
    for line in text.split("\n"):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if fenced:
            lines.append(line)
            continue
        if line.startswith("    ") and (indented or previous_blank):
            indented = True
            lines.append(line.strip())
        elif line.strip():
            indented = False
        previous_blank = not line.strip()
    # join continuation lines
    joined, pending = [], ""
    for line in lines:
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1] + " "
            continue
        joined.append(pending + line)
        pending = ""
    return joined


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", required=True)
    parser.add_argument("--program", action="append", default=[])
    args = parser.parse_args()
    root = pathlib.Path(args.root)
    documents = [root / "README.md", *sorted((root / "docs").glob("*.md"))]
    failures = []

    # 1. Links.
    texts = {d: d.read_text(encoding="utf-8") for d in documents}
    links = 0
    for document, text in texts.items():
        # inline code can hold brackets that are not links
        prose = re.sub(r"`[^`\n]*`", "", text)
        for target in re.findall(r"\]\(([^)\s]+)\)", prose):
            if re.match(r"^[a-z]+:", target):
                continue
            links += 1
            path, _, fragment = target.partition("#")
            file = (document.parent / path).resolve() if path else document
            if not file.exists():
                failures.append(f"{document.relative_to(root)}: link {target}: no file {path}")
                continue
            if fragment and file.suffix == ".md" and fragment not in anchors(file.read_text(encoding="utf-8")):
                failures.append(f"{document.relative_to(root)}: link {target}: no heading '#{fragment}' in {path or document.name}")

    # 2. Commands.
    helps = {}
    for entry in args.program:
        name, _, path = entry.partition("=")
        r = subprocess.run([path, "--help"], capture_output=True, text=True, timeout=60)
        if r.returncode != 0:
            failures.append(f"{name} --help exited {r.returncode}: {(r.stdout + r.stderr).strip()[:200]}")
            continue
        helps[name] = r.stdout + r.stderr
    commands = 0
    for document, text in texts.items():
        for line in code_lines(text):
            words = line.split()
            for i, word in enumerate(words):
                name = word.rsplit("/", 1)[-1]
                if name not in helps:
                    continue
                commands += 1
                # the flags of this command: up to the next program or shell operator
                rest = []
                for w in words[i + 1:]:
                    if w in ("|", "&&", ";", "||", ">", "2>") or w.rsplit("/", 1)[-1] in helps:
                        break
                    rest.append(w)
                for flag in re.findall(r"(?<![\w-])--(?:\[no-\])?[a-z0-9][a-z0-9-]*", " ".join(rest)):
                    plain = flag.replace("[no-]", "")
                    if flag not in helps[name] and plain not in helps[name]:
                        failures.append(f"{document.relative_to(root)}: `{name} … {flag}`: {flag} is not in {name} --help")
                break

    for failure in failures:
        print(f"FAIL {failure}")
    print(f"docs: {len(documents)} documents, {links} relative links, {commands} commands of "
          f"{', '.join(sorted(helps))} checked against their --help, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
