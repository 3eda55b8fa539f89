"""Strict CSV reading shared by the run and thesis readers: typed columns, line-numbered errors."""

import csv
import gzip
import io
import math
from pathlib import Path


class InputError(Exception):
    """An input file that cannot be read as documented; str() is the one-line message to print."""


def read_typed_csv(path: Path, required, int_columns=(), float_columns=(), choices=None, need_rows=False):
    """Rows of `path` as dicts; the header must name every column in `required`; with `need_rows`, a file
    holding only its header is refused too (a file cut off after its first line, or written by a run that
    measured nothing).

    `choices` maps a column to the values it may hold.

    Extra columns are kept as strings so that a runner adding columns does not break the report.
    Times must be finite and non-negative: a NaN or negative time is a broken measurement, not data.
    A path ending in .gz is read through gzip (committed results keep frames.csv compressed).
    """
    line = 0
    try:
        with _open_text(path) as f:
            reader = csv.reader(f)
            header = next(reader, None)
            if header is None:
                raise InputError(f"{path}: empty file, expected a CSV header")
            header = [h.strip() for h in header]
            missing = [c for c in required if c not in header]
            if missing:
                raise InputError(f"{path}:1: the header lacks column(s) {', '.join(missing)} "
                                 f"(needed: {', '.join(required)})")
            rows = []
            for row in reader:
                line = reader.line_num
                if not row or all(not cell.strip() for cell in row):
                    continue
                if len(row) != len(header):
                    try:
                        last = next(reader, None) is None
                    except (csv.Error, OSError, EOFError, UnicodeDecodeError):
                        last = True     # what follows is broken too: the file ends there, as far as it reads
                    raise InputError(_field_count_message(path, line, header, row, last))
                record = dict(zip(header, (cell.strip() for cell in row)))
                for name in int_columns:
                    if name in record:
                        record[name] = _parse_int(path, line, name, record[name])
                for name in float_columns:
                    if name in record:
                        record[name] = _parse_time(path, line, name, record[name])
                for name, allowed in (choices or {}).items():
                    if record.get(name) not in allowed:
                        raise InputError(f"{path}:{line}: column {name}: expected one of "
                                         f"{', '.join(allowed)}, got {record.get(name)!r}")
                rows.append(record)
            if need_rows and not rows:
                raise InputError(f"{path}: only its header (line 1), no rows: the file was cut off after its first "
                                 f"line or its run measured nothing; run it again or remove the file")
            return rows
    except csv.Error as e:
        raise InputError(f"{path}:{line + 1}: not CSV: {e}") from e
    except (OSError, EOFError, UnicodeDecodeError) as e:
        where = f":{line + 1}" if line else ""
        raise InputError(f"{path}{where}: cannot read: {e}") from e


def _field_count_message(path, line, header, row, last):
    """A row whose field count is not the header's: how many of which columns, and where a short row stops
    (the last line of a file cut off mid-row, most often)."""
    text = (f"{path}:{line}: expected {len(header)} columns ({_span(header)}), found {len(row)}")
    if len(row) < len(header):
        text += f": the row ends in column {header[len(row) - 1]}"
        if last:
            text += " and is the file's last line: the file was cut off mid-row"
    else:
        text += f": {len(row) - len(header)} more than the header names"
    return text


def _span(names):
    """'a, b, c' for a few names; 'a, b, ..., z' for many."""
    return ", ".join(names) if len(names) <= 4 else f"{names[0]}, {names[1]}, ..., {names[-1]}"


def _parse_int(path, line, name, text):
    try:
        return int(text)
    except ValueError:
        raise InputError(f"{path}:{line}: column {name}: expected an integer, got {text!r}") from None


def _parse_time(path, line, name, text):
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{path}:{line}: column {name}: expected a number, got {text!r}") from None
    if not math.isfinite(value) or value < 0:
        raise InputError(f"{path}:{line}: column {name}: expected a finite non-negative number, got {text!r}")
    return value


def _open_text(path: Path):
    """`path` for reading as UTF-8 CSV text, decompressed when its name ends in .gz; NAME.gz.00 is the
    first of the parts NAME.gz.00, NAME.gz.01, ... that scripts/pack-results.sh cuts a file over 1 MiB
    into, read as the file they make together."""
    path = Path(path)
    if path.name.endswith(".gz.00"):
        stem = path.name[: -len("00")]
        parts = sorted(p for p in path.parent.glob(stem + "*") if p.name[len(stem):].isdigit())
        whole = io.BytesIO(b"".join(p.read_bytes() for p in parts))
        return gzip.open(whole, "rt", newline="", encoding="utf-8")
    if path.suffix == ".gz":
        return gzip.open(path, "rt", newline="", encoding="utf-8")
    return open(path, newline="", encoding="utf-8")
