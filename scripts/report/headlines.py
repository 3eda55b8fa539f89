#!/usr/bin/python3
"""The few lines of a REPORT.md a reader wants first, read back from the file scripts/report.py wrote
(scripts/reproduce.sh prints them at its end):

  Correctness: 0 false negatives in every environment and strategy (4530 frames checked against the ground truth)
  env1 on cpu, 1320 frames: cullide/ours 1.26 (thesis 2.09), cullide_bvh/ours 2.65 (thesis 1.67); 4 findings agree with the thesis, 10 differ
  ...
  Does the culling pay on cpu? vs all_pairs: pays in env2 (ours/all_pairs 0.90) ...; vs FCL: does not pay in ...
  Precision, what ours loses in raw mode: env1 84.3% at 32 px, 1.9% at 128 px, none from 256 px; ...

Usage: python3 scripts/report/headlines.py REPORT.md [--max N]
Standard library only; a section the report lacks (or words it no longer uses) gives no line, not an error.
"""

import re
import sys
from pathlib import Path

# The thesis' two comparisons with ours, each a row of an environment's speedup table.
SPEEDUPS = ("cullide", "cullide_bvh")
REFERENCE = "ours"
MAX_LINES = 8


def headlines(text, limit=MAX_LINES):
    """Up to `limit` lines: correctness, one per environment of the summary, whether the culling pays (one per
    backend), and what ours loses in raw mode."""
    sections = _sections(text.splitlines())
    out = []
    environments = []
    for bullet in _bullets(sections.get("## Summary", [])):
        if bullet.startswith(("Correctness:", "**FALSE NEGATIVES", "**Not checked")):
            out.append(_correctness(bullet))
            continue
        m = re.match(r"\*\*([^*]+)\*\*(?: on (\S+))?: (.*)$", bullet)
        if m:
            environments.append(_environment(m.group(1), m.group(2), m.group(3), sections))
    out += environments
    for bullet in _bullets(sections.get("## Does the culling pay?", [])):
        m = re.match(r"\*\*([^*]+)\*\*: (.*)$", bullet)
        if m and not m.group(2).startswith("no "):     # "no all_pairs or fcl rows to set the culling against"
            verdict = re.sub(r"against (\S+)(?: \([^)]*\))? the culling ", r"vs \1: ", m.group(2).replace("`", ""))
            out.append(f"Does the culling pay on {m.group(1)}? {verdict.rstrip('.')}")
    precision = _precision(sections.get("### What is lost where", []))
    if precision:
        out.append(precision)
    return out[:limit]


def _sections(lines):
    """Heading line -> the lines under it up to the next heading (the first of equal headings wins)."""
    sections, current = {}, None
    for line in lines:
        if line.startswith("#"):
            current = line.strip()
            if current in sections:
                current = None
            else:
                sections[current] = []
        elif current is not None:
            sections[current].append(line)
    return sections


def _bullets(lines):
    return [line[2:].strip() for line in lines if line.startswith("- ")]


def _correctness(bullet):
    text = bullet.replace("**", "")
    text = text.split(". These strategies")[0]
    return re.sub(r"\): no colliding pair was culled or split across sets\.", ")", text).rstrip(".")


def _environment(name, backend, rest, sections):
    where = f"{name} on {backend}" if backend else name
    frames = re.search(r", (\d+) frames; ", rest)
    if not frames:
        return f"{where}: {rest.rstrip('.')}"     # not run, no frames, unfinished
    parts = []
    table = next((lines for heading, lines in sections.items()
                  if heading.startswith(f"#### {name}: speedup of {REFERENCE}")), [])
    for strategy in SPEEDUPS:
        for line in table:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if cells and cells[0] == f"{strategy} / {REFERENCE}, average" and re.match(r"[0-9]", cells[-1]):
                parts.append(f"{strategy}/{REFERENCE} {cells[-1]}")
                break
    findings = re.search(r"(\d+) finding\(s\) agree with the thesis, (\d+) differ", rest)
    text = f"{where}, {frames.group(1)} frames"
    if parts:
        text += ": " + ", ".join(parts)
    if findings:
        text += f"{';' if parts else ':'} {findings.group(1)} findings agree with the thesis, {findings.group(2)} differ"
    return text


def _precision(lines):
    """'Precision, what ours loses in raw mode: env1 ...; env2 ...' from the study's "What is lost where"."""
    parts = []
    for bullet in _bullets(lines):
        m = re.match(r"\*\*([^*]+)\*\*.*?raw mode loses: (.*)$", bullet)
        if not m:
            continue
        clause = next((c.strip().rstrip(".") for c in m.group(2).split(";")
                       if c.strip().startswith(f"{REFERENCE} ")), None)
        if clause:
            parts.append(f"{m.group(1)} {clause[len(REFERENCE) + 1:]}")
    return f"Precision, what {REFERENCE} loses in raw mode: " + "; ".join(parts) if parts else None


def main(argv):
    if not argv or argv[0].startswith("-"):
        print("usage: headlines.py REPORT.md [--max N]", file=sys.stderr)
        return 2
    limit = int(argv[2]) if len(argv) >= 3 and argv[1] == "--max" else MAX_LINES
    try:
        text = Path(argv[0]).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as e:
        print(f"headlines.py: {argv[0]}: cannot read: {e}", file=sys.stderr)
        return 2
    for line in headlines(text, limit):
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
