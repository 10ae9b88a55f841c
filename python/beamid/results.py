"""A study's results (``results/<study>/*.csv``, as ``beamid study`` writes them) as NumPy structured arrays.

A column whose every field reads as a number (NaN and empty fields included) is float64, any other column text;
quoted fields may hold commas, as the program quotes them.
"""
import csv
import json
import os
import re

import numpy as np


def _check_as_dict(function, as_dict):
    # A bool, as every switch of the package: "no" is truthy, and gave dicts (the twenty-ninth pass's adv66 P6).
    if not isinstance(as_dict, (bool, np.bool_)):
        raise TypeError(f"{function}(): as_dict = {as_dict!r}: must be a bool")


def read_table(path, as_dict=False):
    """One CSV table: a structured array (one field per column), or with ``as_dict`` a dict of column arrays."""
    # utf-8-sig: a byte-order mark (as spreadsheets write one) is no part of the first column's name.
    # As the command line reads a user's file: a pipe or a device is refused, not waited on or read without end, and
    # a table past 1 GiB is no table beamid wrote (a FIFO hung and /dev/zero ran to a MemoryError: the twenty-second
    # pass's P11).
    if not isinstance(path, (str, bytes, os.PathLike)):
        raise TypeError(f"read_table(): path = {path!r}: must be a str or an os.PathLike (the table's file)")
    _check_as_dict("read_table", as_dict)
    if not os.path.isfile(path):
        raise ValueError(f"{path}: not a regular file (a folder, a pipe or a device): a results table is a CSV file")
    if os.path.getsize(path) > 1 << 30:
        raise ValueError(f"{path}: {os.path.getsize(path)} bytes: more than the 1073741824 a results table may have")
    with open(path, newline="", encoding="utf-8-sig") as f:
        try:
            rows = list(csv.reader(f, strict=True))  # strict: an unclosed quote is an error, not a field to the end
        except csv.Error as error:
            raise ValueError(f"{path}: not a CSV table as beamid writes them: {error}") from None
        except UnicodeDecodeError as error:
            raise ValueError(f"{path}: not a text table (byte {error.start} is not UTF-8): beamid writes its tables "
                             f"as UTF-8 CSV") from None
    if not rows:
        raise ValueError(f"{path}: empty file: a results table starts with a header line")
    # A control byte (NUL, ...) is in no table beamid writes: a binary file was read as a table with one column named
    # by its bytes (the twenty-third pass's P3).
    for line, row in enumerate(rows, start=1):
        for field in row:
            bad = next((c for c in field if ord(c) < 32 and c not in "\t\r\n"), None)
            if bad is not None:
                raise ValueError(f"{path}:{line}: byte 0x{ord(bad):02X}, a control character: a binary file, not a "
                                 f"results table (beamid writes its tables as text)")
    header, body = rows[0], rows[1:]
    # A Markdown table (beamid writes one beside each CSV) is no CSV table (the twenty-fourth pass's adv56 P7).
    if header and header[0].lstrip().startswith("|"):
        raise ValueError(f"{path}:1: a Markdown table ('|' columns): read the .csv table beside it")
    if len(header) == 1 and ";" in header[0]:
        raise ValueError(f"{path}:1: one column named {header[0]!r}: a table separated by ';' is not one beamid writes "
                         f"(its tables are comma-separated)")
    for j, name in enumerate(header, start=1):
        if not name.strip() or any(c in name for c in "\r\n\"") or name != name.strip():
            raise ValueError(f"{path}:1: column {j} is named {name!r}: a results table's header names each column "
                             f"(no blank, quoted or multi-line names)")
    repeated = sorted({name for name in header if header.count(name) > 1})
    if repeated:
        raise ValueError(f"{path}:1: column name(s) {', '.join(repeated)} given twice: each column has its own name")
    for line, row in enumerate(body, start=2):
        if len(row) != len(header):
            raise ValueError(f"{path}:{line}: {len(row)} fields: the header names {len(header)}")
    columns = {}
    for j, name in enumerate(header):
        fields = [row[j] for row in body]
        columns[name] = _column(fields)
    if as_dict:
        return columns
    dtype = [(name, column.dtype) for name, column in columns.items()]
    table = np.zeros(len(body), dtype=dtype)
    for name, column in columns.items():
        table[name] = column
    return table


_INTEGER = re.compile(r"[+-]?[0-9]+")
_LEADING_ZERO = re.compile(r"[+-]?0[0-9]+")
_NUMBER = re.compile(r"[+-]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][+-]?[0-9]+)?")
_WORDS = {"nan", "+nan", "-nan", "inf", "+inf", "-inf", "infinity", "+infinity", "-infinity"}


def _column(fields):
    """A column's values: integers as int64 (uint64 beyond it) when every field is a plain integer; numbers as float
    (empty cells NaN) when every field is a number float holds exactly enough; else text. A 64-bit seed read as a
    float lost its last digits (8633401241432287573 came back ...7232), an identifier with a leading zero lost the
    zero, "1_0" (Python's digit grouping) became 10 and "1234567e89012345" inf (the twenty-third pass's adv56 P1,
    the twenty-fifth's adv58 P4): such a column stays exact or text."""
    plain = [x.strip() for x in fields]
    filled = [x for x in plain if x and x.lower() not in _WORDS]
    text = np.array(fields, dtype=str)
    if filled and all(_INTEGER.fullmatch(x) for x in filled):
        if any(_LEADING_ZERO.fullmatch(x) for x in filled):
            return text  # identifiers: "007" is no 7
        values = [int(x) for x in filled]
        if len(filled) == len(plain):
            if all(-(1 << 63) <= v < (1 << 63) for v in values):
                return np.array(values, dtype=np.int64)
            if all(0 <= v < (1 << 64) for v in values):
                return np.array(values, dtype=np.uint64)
            return text
        if any(abs(v) > 1 << 53 for v in values):
            return text  # a float, needed for the empty cells, would round them
    if not all(_NUMBER.fullmatch(x) for x in filled):
        return text
    numbers = [float(x) if x else np.nan for x in plain]
    if any(np.isinf(v) for v, x in zip(numbers, plain) if x and x.lower() not in _WORDS):
        return text  # beyond a double's range: no number beamid wrote
    return np.array(numbers, dtype=float)


def load_results(folder, as_dict=False):
    """Every CSV table of a study's results folder, by name without ``.csv`` (``cases``, ``summary``, ...; those of its
    ``landscape/`` and ``start_distance/`` folders as ``landscape/<name>``, ``start_distance/<name>``): structured
    arrays, or with ``as_dict`` dicts of column arrays. The folder's manifest.json is under ``"manifest"`` as a dict.
    A folder without manifest.json is refused: it is not one that beamid study or beamid real wrote (whatever CSV
    files it held were returned as if they were a study's tables)."""
    if not isinstance(folder, (str, os.PathLike)) or isinstance(folder, bytes):
        raise TypeError(f"load_results(): folder = {folder!r}: must be a str or an os.PathLike (the results folder)")
    _check_as_dict("load_results", as_dict)
    if not os.path.isdir(folder):
        raise FileNotFoundError(f"{folder}: not a results folder (beamid study writes results/<study>/)")
    manifest_path = os.path.join(folder, "manifest.json")
    if os.path.lexists(manifest_path) and not os.path.isfile(manifest_path):  # a folder was "no manifest" (adv68 P5)
        raise ValueError(f"{manifest_path}: not a regular file (a folder, a pipe or a broken link): not the "
                         "manifest.json beamid writes")
    if not os.path.isfile(manifest_path):
        raise ValueError(f"{folder}: no manifest.json: not a results folder that beamid study or beamid real wrote "
                         "(a shard's folder gets its tables from beamid merge)")
    tables = {}
    # The tables of the subfolders a study writes too, as "landscape/<name>" and "start_distance/<name>" (they were
    # left out: the twenty-second pass's P6).
    for sub in ("", "landscape", "start_distance"):
        where = os.path.join(folder, sub)
        if not os.path.isdir(where):
            continue
        for name in sorted(os.listdir(where)):
            path = os.path.join(where, name)
            if not name.endswith(".csv"):
                continue
            if not os.path.isfile(path):  # left out silently (the thirty-first pass's adv70 P2)
                raise ValueError(f"{path}: not a regular file (a folder, a pipe or a broken link): not a table "
                                 "beamid writes")
            tables[(sub + "/" if sub else "") + name[:-4]] = read_table(path, as_dict=as_dict)
    manifest = os.path.join(folder, "manifest.json")
    if os.path.getsize(manifest) > 1 << 26:
        raise ValueError(f"{manifest}: {os.path.getsize(manifest)} bytes: more than the 67108864 a manifest may have")
    with open(manifest, encoding="utf-8") as f:
        try:
            tables["manifest"] = json.load(f)
        # Named: it named no file (the twenty-second pass's P15), nor did Python's own limits on nesting and on an
        # integer's digits (the thirty-first pass's adv70 P6).
        except (json.JSONDecodeError, UnicodeDecodeError, RecursionError, ValueError) as error:
            raise ValueError(f"{manifest}: not the manifest.json beamid writes: {error}") from None
    # An object, as beamid writes it (a list, a string or a number was returned as the manifest: adv66 P6).
    if not isinstance(tables["manifest"], dict):
        raise ValueError(f"{manifest}: not the manifest.json beamid writes: a JSON "
                         f"{type(tables['manifest']).__name__}, not an object")
    # A study's cases.csv holds the cases its manifest counts: one cut at a line boundary read as complete (the
    # thirty-first pass's adv70 P1: 5 rows of 12).
    expected = tables["manifest"].get("cases")
    if "cases" in tables and isinstance(expected, int) and not isinstance(expected, bool):
        rows = len(next(iter(tables["cases"].values()))) if as_dict else len(tables["cases"])
        if rows != expected:
            raise ValueError(f"{os.path.join(folder, 'cases.csv')}: {rows} rows, but manifest.json counts {expected} "
                             "cases: cut short or from another run (rerun beamid study to rewrite it)")
    return tables
