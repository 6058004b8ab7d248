#!/usr/bin/env python3
"""Runs every command shown in README.md and docs/*.md and checks what the text says about it.

Blocks (fenced code in the markdown):
  ```sh      each line is a command (a trailing '\\' continues it); it must exit with status 0.
             A block that shows no bssrdf command (set-up, cmake) is not run.
  ```console '$ COMMAND' lines (also a plain ``` block whose lines start with '$ '), each followed by the output the text shows: the command must exit
             with status 0 (2 when the shown output starts 'bssrdf: error'), and every shown line
             must appear in its stdout + stderr, whitespace-insensitive; '...' in a shown line elides
             text (each piece must appear, in order).
Other fences (json, cpp, plain ```) are not commands and are not run.

A marker in the line just before a fence changes that block:
  <!-- doc-test: skip REASON -->     not run; the reason is printed and counted (kept rare)
  <!-- doc-test: exit N -->          every command of the block must exit with status N
  <!-- doc-test: setup COMMAND -->   run COMMAND first (hidden from the reader), e.g. to make a file

Commands of one page run in order in one scratch directory, so a later command can use a file an
earlier one wrote; `bssrdf` is the binary under test (first argument), and the repository's
`materials/` and `tests/data/` are reachable as `$BSSRDF_REPO/...`.

The README stays a front door: more than README_MAX_LINES lines fails the test.

Usage: run_doc_commands.py BSSRDF_BINARY [PAGE.md ...]   (default: README.md and docs/*.md)
       run_doc_commands.py BSSRDF_BINARY --self-test     (the checker catches wrong output and status)
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
README_MAX_LINES = 250
TIMEOUT = 300  # seconds per command: a documented command that takes longer belongs in tools/


def blocks(text):
    """Yields (line number, language, marker, body lines) for each fenced block."""
    lines = text.split("\n")
    i = 0
    while i < len(lines):
        m = re.match(r"^```(\w*)\s*$", lines[i])
        if not m:
            i += 1
            continue
        start, language = i, m.group(1)
        marker = None
        j = start - 1
        while j >= 0 and not lines[j].strip():
            j -= 1
        if j >= 0:
            mm = re.match(r"^<!--\s*doc-test:\s*(.*?)\s*-->\s*$", lines[j])
            if mm:
                marker = mm.group(1)
        i += 1
        body = []
        while i < len(lines) and not lines[i].startswith("```"):
            body.append(lines[i])
            i += 1
        i += 1
        yield start + 1, language, marker, body


def commands_of_sh(body):
    out, current = [], ""
    for line in body:
        if line.rstrip().endswith("\\"):
            current += line.rstrip()[:-1] + " "
            continue
        current += line
        if current.strip() and not current.strip().startswith("#"):
            out.append((current.strip(), None))
        current = ""
    return out


def commands_of_console(body):
    out = []
    for line in body:
        if line.startswith("$ "):
            out.append([line[2:].strip(), []])
        elif out:
            out[-1][1].append(line)
    return [(c, shown) for c, shown in out]


def squash(text):
    return re.sub(r"\s+", " ", text).strip()


def check_shown(shown, actual):
    """The shown lines that the actual output no longer says."""
    missing = []
    said = squash(actual)
    for line in shown:
        if not line.strip():
            continue
        position = 0
        for piece in (squash(p) for p in line.split("...")):
            if not piece:
                continue
            found = said.find(piece, position)
            if found < 0:
                missing.append(line)
                break
            position = found + len(piece)
    return missing


def run_page(page, binary, env):
    failures, ran, skipped = [], 0, []
    text = page.read_text(encoding="utf-8")
    with tempfile.TemporaryDirectory(prefix="bssrdf-doc-") as cwd:
        for line_number, language, marker, body in blocks(text):
            if language in ("sh", "bash", "shell"):
                commands = commands_of_sh(body)
            elif language == "console" or (language == "" and any(l.startswith("$ ") for l in body)):
                commands = commands_of_console(body)
            else:
                continue
            # A block is run when it shows a bssrdf command; its other lines (mkdir, cp) run with it.
            if not any(re.search(r"(^|[|;&(]\s*)bssrdf\b", c) for c, _ in commands):
                continue
            where = f"{page.name if binary is None else page.relative_to(REPO)}:{line_number}"
            expected = None
            if marker:
                kind, _, argument = marker.partition(" ")
                if kind == "skip":
                    if not argument.strip():
                        failures.append(f"{where}: 'doc-test: skip' needs a reason")
                    skipped.append(f"{where}: {argument.strip()} ({len(commands)} commands)")
                    continue
                if kind == "exit":
                    expected = int(argument)
                elif kind == "setup":
                    subprocess.run(argument, shell=True, cwd=cwd, env=env, timeout=TIMEOUT, check=True,
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                else:
                    failures.append(f"{where}: unknown marker 'doc-test: {marker}'")
                    continue
            for command, shown in commands:
                ran += 1
                try:
                    p = subprocess.run(command, shell=True, cwd=cwd, env=env, timeout=TIMEOUT,
                                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                       executable="/bin/bash")
                except subprocess.TimeoutExpired:
                    failures.append(f"{where}: `{command}` ran longer than {TIMEOUT} s")
                    continue
                want = expected
                if want is None:
                    want = 2 if shown and any(l.startswith("bssrdf: error") for l in shown) else 0
                if p.returncode != want:
                    failures.append(f"{where}: `{command}` exited {p.returncode}, expected {want}: "
                                    f"{(p.stderr or p.stdout).strip()[-400:]}")
                    continue
                missing = check_shown(shown or [], p.stdout + p.stderr)
                if missing:
                    failures.append(f"{where}: `{command}` no longer prints: {missing[0]!r}\n  it printed: "
                                    f"{(p.stdout + p.stderr)[:600]!r}")
    return failures, ran, skipped


SELF_TEST_PAGES = {
    # page text -> the number of failures the checker must report
    "```sh\nbssrdf --version\n```\n": 0,
    "```console\n$ bssrdf --version\nbssrdf 0.0.0-not-this-version\n```\n": 1,
    "```sh\nbssrdf profile --materail Skin1\n```\n": 1,
    "<!-- doc-test: exit 2 -->\n```sh\nbssrdf profile --materail Skin1\n```\n": 0,
    "```console\n$ bssrdf profile --materail Skin1\nbssrdf: error: unknown option ... did you mean '--material'?\n```\n": 0,
    "<!-- doc-test: skip -->\n```sh\nbssrdf --version\n```\n": 1,  # a skip needs its reason
}


def self_test(env):
    wrong = 0
    with tempfile.TemporaryDirectory(prefix="bssrdf-doc-self-") as directory:
        for i, (text, expected) in enumerate(SELF_TEST_PAGES.items()):
            page = Path(directory) / f"page{i}.md"
            page.write_text(text, encoding="utf-8")
            failures, _, _ = run_page(page, None, env)
            if len(failures) != expected:
                wrong += 1
                print(f"self-test: {text!r}: {len(failures)} failures, expected {expected}: {failures}")
    print(f"doc test self-test: {len(SELF_TEST_PAGES) - wrong} of {len(SELF_TEST_PAGES)} pages judged right")
    return 1 if wrong else 0


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    binary = Path(sys.argv[1]).resolve()
    pages = [Path(p).resolve() for p in sys.argv[2:] if p != "--self-test"]
    pages = pages or [REPO / "README.md"] + sorted((REPO / "docs").glob("*.md"))
    with tempfile.TemporaryDirectory(prefix="bssrdf-doc-bin-") as bin_dir:
        os.symlink(binary, Path(bin_dir) / "bssrdf")
        env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ.get("PATH", ""), BSSRDF_REPO=str(REPO))
        if "--self-test" in sys.argv[2:]:
            return self_test(env)
        readme_lines = (REPO / "README.md").read_text(encoding="utf-8").count("\n")
        if readme_lines > README_MAX_LINES:
            print(f"FAILED: README.md has {readme_lines} lines, more than {README_MAX_LINES}: move detail to docs/")
            return 1
        all_failures, total, all_skipped = [], 0, []
        for page in pages:
            failures, ran, skipped = run_page(page, binary, env)
            all_failures += failures
            all_skipped += skipped
            total += ran
            print(f"{page.relative_to(REPO)}: {ran} commands run, {len(skipped)} blocks skipped, "
                  f"{len(failures)} failures", flush=True)
    for s in all_skipped:
        print("skipped:", s)
    for f in all_failures:
        print("FAILED:", f)
    print(f"README.md: {readme_lines} lines (at most {README_MAX_LINES})")
    print(f"doc test: {total} commands run from {len(pages)} pages, {len(all_skipped)} blocks skipped, "
          f"{len(all_failures)} failures")
    return 1 if all_failures else 0


if __name__ == "__main__":
    sys.exit(main())
