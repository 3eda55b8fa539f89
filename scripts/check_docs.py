#!/usr/bin/python3
"""Checks that README.md and docs/*.md cannot drift from the repository and the program.

- Every relative link (Markdown links and images, HTML src/href) names a file or folder that exists,
  and an anchor (#section) names a heading of the page it points to (GitHub's heading ids).
- Every source file a page names by its path (harness/run/RunPlan.h, scripts/reproduce.sh: a path under
  one of the code folders with a source file's ending) exists, so moving code cannot strand a page.
- Every `cdbench SUBCOMMAND --option` written in a code span or block names a subcommand the CLI
  accepts and options that subcommand accepts, as the program's own --help lists them.

Usage: scripts/check_docs.py [--cdbench build/cdbench] [FILE.md ...]
With no files: README.md and every .md under docs/. Exit 0 when all is well, 1 when anything is
wrong (one line each, FILE:LINE: what), 2 on bad usage (no binary).
"""

import argparse
import difflib
import os
import re
import shlex
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# [text](target) and ![alt](target), the target up to a space (a title may follow) or ')'.
MARKDOWN_LINK = re.compile(r"!?\[(?:[^\]\[]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
# Reference-style definitions: [name]: target
REFERENCE_LINK = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
HTML_LINK = re.compile(r"""<(?:img|a|source)\b[^>]*?\b(?:src|href)\s*=\s*["']([^"']+)["']""", re.IGNORECASE)
EXTERNAL = re.compile(r"^(?:[a-z][a-z0-9+.-]*:|//)", re.IGNORECASE)
CODE_SPAN = re.compile(r"(`+)(.+?)\1")
FENCE = re.compile(r"^\s{0,3}(```+|~~~+)")
# A program invocation: cdbench, build/cdbench, ./build-asan/cdbench, "$CDBENCH" is not one.
CDBENCH = re.compile(r"(?:^|(?<=[\s(;&|`'\"=]))(?:[\w./-]*/)?cdbench(?=\s|$)")
# A source file named by its path from the repository's root, in prose or code.
SOURCE_PATH = re.compile(r"(?<![\w./-])((?:harness|culling|scenes|core|render|tests|bench|fuzz|scripts|cmake)"
                         r"/[\w./+-]*\.(?:h|hpp|cpp|cc|py|sh|cmake|txt|sbatch|supp))(?![\w/-])")
# What ends one command on a line.
SHELL_BREAK = {"|", "||", "&&", ";", "&", ">", ">>", "2>", "2>&1", "<", ")", "#"}


@dataclass
class Cli:
    """The subcommands of the program and the options each accepts (global ones included)."""
    global_options: set
    subcommands: dict = field(default_factory=dict)  # name -> set of options


def help_section(text, titles):
    """The first column of each entry of a CLI11 --help section ("Options:", "Subcommands:")."""
    in_section = False
    for line in text.splitlines():
        if re.match(r"^\S.*:\s*$", line):
            in_section = line.strip().rstrip(":").lower() in titles
            continue
        m = re.match(r"^ {2}(\S+)", line)
        if in_section and m:
            yield m.group(1)


def help_options(text):
    """The option names a --help lists: "-h,--help" gives -h and --help, "--out=DIR" --out."""
    return {name.split("=")[0] for entry in help_section(text, ("options",))
            for name in entry.split(",") if name.startswith("-")}


def help_subcommands(text):
    return [entry for entry in help_section(text, ("subcommands",)) if re.fullmatch(r"[a-z][\w-]*", entry)]


def read_cli(binary):
    def help_of(*args):
        done = subprocess.run([binary, *args, "--help"], capture_output=True, text=True, timeout=60)
        if done.returncode != 0:
            raise RuntimeError(f"{binary} {' '.join(args)} --help exited {done.returncode}: {done.stderr.strip()}")
        return done.stdout

    top = help_of()
    cli = Cli(global_options=help_options(top))
    for name in help_subcommands(top):
        cli.subcommands[name] = help_options(help_of(name)) | cli.global_options
    if not cli.subcommands:
        raise RuntimeError(f"{binary} --help lists no subcommands")
    return cli


def heading_ids(markdown_text):
    """GitHub's ids for a page's headings: lower case, punctuation dropped, spaces to hyphens,
    repeats numbered -1, -2, ..."""
    ids, seen = set(), {}
    in_fence = False
    for line in markdown_text.splitlines():
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        m = None if in_fence else re.match(r"^\s{0,3}#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        text = re.sub(r"<[^>]+>", "", m.group(1))
        text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link's text only
        slug = re.sub(r"[^\w\- ]", "", text.strip().lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        ids.add(slug if n == 0 else f"{slug}-{n}")
        seen[slug] = n + 1
    return ids


def link_problem(page, target):
    """What is wrong with a relative link from `page`, or None."""
    if EXTERNAL.match(target):
        return None
    path_part, _, anchor = target.partition("#")
    path_part = path_part.split("?")[0]
    dest = page if not path_part else (page.parent / path_part)
    if path_part.startswith("/"):
        dest = ROOT / path_part.lstrip("/")
    dest = Path(os.path.normpath(dest))
    if not dest.exists():
        return f"link {target!r}: {os.path.relpath(dest, ROOT)} does not exist"
    if anchor and dest.is_file() and dest.suffix.lower() == ".md":
        if anchor.lower() not in heading_ids(dest.read_text(encoding="utf-8")):
            return f"link {target!r}: {os.path.relpath(dest, ROOT)} has no heading with id #{anchor}"
    return None


def code_texts(markdown_text):
    """(line number, text, whether fenced) of every code line: fenced blocks' lines (a trailing backslash joins the
    next line) and inline code spans."""
    out, in_fence, pending, pending_line = [], False, "", 0
    for number, line in enumerate(markdown_text.splitlines(), start=1):
        if FENCE.match(line):
            in_fence = not in_fence
            pending = ""
            continue
        if in_fence:
            if not pending:
                pending_line = number
            if line.rstrip().endswith("\\"):
                pending += line.rstrip()[:-1] + " "
                continue
            out.append((pending_line, pending + line, True))
            pending = ""
        else:
            for m in CODE_SPAN.finditer(line):
                out.append((number, m.group(2), False))
    return out


def command_problems(text, cli, counts=None, fenced=True):
    """What is wrong with each `cdbench ...` invocation in one line of code; `counts` (a dict) gets
    how many invocations were checked."""
    problems = []
    for m in CDBENCH.finditer(text):
        rest = text[m.end():]
        try:
            words = shlex.split(rest, comments=False, posix=True)
        except ValueError:
            words = rest.split()
        if not words:
            continue  # the program's name alone, e.g. "the cdbench binary"
        sub = words[0]
        if sub in SHELL_BREAK or sub.startswith(("$", "<", "[", "{", "…", "...")):
            continue
        if sub.startswith("-"):
            if sub.split("=")[0] not in cli.global_options:
                problems.append(f"`cdbench {sub}`: the CLI has no global option {sub}")
            continue
        if not re.fullmatch(r"[a-z][\w-]*", sub):
            continue  # prose in a code span ("cdbench's"), not a command
        if sub not in cli.subcommands:
            # In a code span a word after the name may be prose (the file format's header text
            # `cdbench scenario v2`): it is a command when an option follows or it is a near miss
            # of a subcommand (a typo). A fenced block holds commands only.
            looks_like_command = fenced or any(w.startswith("-") for w in words[1:]) or \
                difflib.get_close_matches(sub, cli.subcommands, n=1, cutoff=0.75)
            if not looks_like_command:
                continue
            problems.append(f"`cdbench {sub}`: the CLI has no subcommand {sub!r} "
                            f"(it has {', '.join(sorted(cli.subcommands))})")
            continue
        if counts is not None:
            counts["commands"] = counts.get("commands", 0) + 1
        for word in words[1:]:
            word = word.strip("[]")  # an optional part written [--option VALUE]
            if word in SHELL_BREAK or word.startswith(("#", "|", ">", "2>", "&", ";")):
                break
            if word.startswith("--") and len(word) > 2:
                name = word.split("=")[0]
                if name not in cli.subcommands[sub]:
                    problems.append(f"`cdbench {sub} {name}`: {sub} has no option {name}")
            elif re.fullmatch(r"-[A-Za-z]", word) and word not in cli.subcommands[sub]:
                problems.append(f"`cdbench {sub} {word}`: {sub} has no option {word}")
    return problems


def check_page(page, cli, counts=None):
    text = page.read_text(encoding="utf-8")
    rel = os.path.relpath(page, ROOT)
    problems = []
    in_fence = False
    for number, line in enumerate(text.splitlines(), start=1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        prose = CODE_SPAN.sub("", line)  # a link written as code is not a link
        targets = [m.group(1) for m in MARKDOWN_LINK.finditer(prose)]
        targets += [m.group(1) for m in HTML_LINK.finditer(prose)]
        ref = REFERENCE_LINK.match(prose)
        if ref:
            targets.append(ref.group(1))
        if counts is not None:
            counts["links"] = counts.get("links", 0) + len(targets)
        for target in targets:
            problem = link_problem(page, target)
            if problem:
                problems.append(f"{rel}:{number}: {problem}")
    for number, line in enumerate(text.splitlines(), start=1):
        for m in SOURCE_PATH.finditer(line):
            if not (ROOT / m.group(1)).exists():
                problems.append(f"{rel}:{number}: {m.group(1)} does not exist")
            elif counts is not None:
                counts["paths"] = counts.get("paths", 0) + 1
    for number, code, fenced in code_texts(text):
        for problem in command_problems(code, cli, counts, fenced):
            problems.append(f"{rel}:{number}: {problem}")
    return problems


def default_pages():
    return [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cdbench", default=os.environ.get("CDBENCH_BINARY", str(ROOT / "build" / "cdbench")),
                        help="the cdbench binary whose --help is the truth (default: $CDBENCH_BINARY, build/cdbench)")
    parser.add_argument("pages", nargs="*", type=Path, help="Markdown files (default: README.md and docs/**/*.md)")
    args = parser.parse_args(argv)
    if not os.access(args.cdbench, os.X_OK):
        print(f"check_docs: {args.cdbench} is not an executable cdbench (build it: scripts/build.sh)", file=sys.stderr)
        return 2
    try:
        cli = read_cli(args.cdbench)
    except (RuntimeError, OSError, subprocess.TimeoutExpired) as e:
        print(f"check_docs: {e}", file=sys.stderr)
        return 2
    pages = [p.resolve() for p in args.pages] or default_pages()
    problems, counts = [], {}
    for page in pages:
        if not page.is_file():
            problems.append(f"{page}: no such file")
            continue
        problems += check_page(page, cli, counts)
    for problem in problems:
        print(problem)
    options = sum(len(v) for v in cli.subcommands.values())
    print(f"check_docs: {len(pages)} pages, {counts.get('links', 0)} links, {counts.get('paths', 0)} source paths, "
          f"{counts.get('commands', 0)} cdbench "
          f"commands against {len(cli.subcommands)} subcommands ({options} options): {len(problems)} problem(s)",
          file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
