#!/usr/bin/python3
"""Stamps on the recorded conformance rows (model.<name>.<property>) of docs/data/claims-*.json.

A row's stamp is a digest of what produced it: the claim id, the budget, and the contents of
every source file its result can depend on, found from the source tree alone. Those files are
the conformance suite's code (verify/conformance/), the batch and ISA code (core/simd/), the
writer of the rows (verify/results.cpp, cli/verify.cpp) and the model's header, each with the
project headers it includes, transitively, and the .cpp beside each header reached (the code
behind a declaration). core/model_list.h, which names every model, is hashed but not followed:
a change to one model leaves the other models' rows as they are. So a change to any file a row
depends on changes the row's expected stamp, and `check` reports the recorded row as stale until
`record` has run it again with the current code.

Usage (Debian's /usr/bin/python3, standard library only):

    row_stamps.py check FILE...
        Exit 0 when every conformance row of each FILE carries the stamp the current sources
        give; otherwise one line per stale or unstamped row on stdout and exit 1.
    row_stamps.py record --glintlab EXE --budget quick|full [--claims GLOBS] [--threads N] FILE
        Runs `EXE verify --budget B --claims GLOBS` (default model.*) in a temporary folder and
        puts each row it wrote into FILE, a conformance row stamped (a paper claim's row carries
        no stamp yet): a row with the same id is replaced, a new one appended; every other row is
        left byte for byte.
    row_stamps.py reproduce --glintlab EXE --budget quick|full [--claims GLOBS] [--threads N] FILE
        Runs the same `verify` as record and compares each conformance row it wrote with the
        row of the same id in FILE, which it leaves as it is: every field but `seconds` and
        `stamp` must be equal (a timing property, model.<name>.constant-time, whose value and
        detail are measured times: its verdict and control verdict). Exit 0 when every row is
        reproduced; otherwise one line per row that is not (its differing fields) and exit 1.
        So a recorded row that the current code no longer produces cannot survive a run of it.
    row_stamps.py files ID
        The files the stamp of claim ID covers, one per line (to see why a row went stale).

Each command takes --source DIR before it: the source tree whose files are hashed (default: the
one this script is in).

A malformed input is one line on stderr (`row_stamps: error: ...`), exit status 2, and nothing
written.
"""

import argparse
import hashlib
import json
import os
import re
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STAMP_VERSION = "glintlab conformance row stamp 1"
# Every file of these folders starts the closure, with these files.
START_DIRS = ("verify/conformance", "core/simd")
START_FILES = ("verify/results.cpp", "cli/verify.cpp")
# Files hashed but not followed: they name every model, so following them would make each row
# depend on every model.
NOT_FOLLOWED = {"core/model_list.h"}
# The row separator of a claims file as `glintlab verify` writes it (a JSON list of objects, two
# spaces of indent).
ROW_SEPARATOR = "\n  },\n  {"
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.MULTILINE)
ROW_ID = re.compile(r'^    "id": "([^"]+)",$', re.MULTILINE)
ROW_BUDGET = re.compile(r'^    "budget": "([^"]+)",$', re.MULTILINE)
ROW_VERDICT = re.compile(r'^    "verdict": "([^"]+)"$', re.MULTILINE)
ROW_STAMP = re.compile(r'^    "stamp": "([^"]+)",\n', re.MULTILINE)


class InputError(Exception):
    pass


def read(path):
    with open(os.path.join(REPO, path), "rb") as f:
        return f.read()


def includes(path):
    """The project files `path` includes (paths from the repository root that exist)."""
    text = read(path).decode("utf-8", errors="replace")
    return [p for p in INCLUDE.findall(text) if os.path.isfile(os.path.join(REPO, p))]


def closure(starts):
    """`starts`, the project headers they include, transitively, and the .cpp beside each header."""
    seen, todo = set(), list(starts)
    while todo:
        path = todo.pop()
        if path in seen:
            continue
        seen.add(path)
        if path in NOT_FOLLOWED:
            continue
        todo.extend(includes(path))
        stem, ext = os.path.splitext(path)
        if ext == ".h" and os.path.isfile(os.path.join(REPO, stem + ".cpp")):
            todo.append(stem + ".cpp")
    return sorted(seen)


def model_header(model):
    """The header that declares the model named `model` (its `kName`)."""
    pattern = re.compile(r'kName\s*=\s*"' + re.escape(model) + '"')
    found = []
    for root, _, files in os.walk(os.path.join(REPO, "core")):
        for name in files:
            if name.endswith(".h"):
                path = os.path.relpath(os.path.join(root, name), REPO)
                if pattern.search(read(path).decode("utf-8", errors="replace")):
                    found.append(path)
    if len(found) != 1:
        raise InputError(f"model '{model}': {len(found)} headers under core/ declare its kName "
                         "(expected exactly one)")
    return found[0]


def conformance_sources():
    files = list(START_FILES)
    for folder in START_DIRS:
        files += [f"{folder}/{n}" for n in os.listdir(os.path.join(REPO, folder))
                  if n.endswith((".h", ".cpp"))]
    return sorted(files)


def covered_files(claim_id):
    parts = claim_id.split(".")
    if len(parts) != 3 or parts[0] != "model":
        raise InputError(f"'{claim_id}' is not a conformance claim (model.<name>.<property>)")
    return closure(conformance_sources() + [model_header(parts[1])])


_file_digests = {}


def file_digest(path):
    if path not in _file_digests:
        _file_digests[path] = hashlib.sha256(read(path)).hexdigest()
    return _file_digests[path]


def expected_stamp(claim_id, budget):
    h = hashlib.sha256()
    h.update(f"{STAMP_VERSION}\nid {claim_id}\nbudget {budget}\n".encode())
    for path in covered_files(claim_id):
        h.update(f"{path} {file_digest(path)}\n".encode())
    return "sha256:" + h.hexdigest()[:32]


def split_rows(text, what):
    """The row chunks of a claims file's text; joining them with ROW_SEPARATOR gives it back."""
    if not text.startswith("[\n  {") or not text.rstrip("\n").endswith("}\n]"):
        raise InputError(f"{what}: not a claims file as glintlab verify writes it")
    return text.split(ROW_SEPARATOR)


def row_field(pattern, chunk, what):
    m = pattern.search(chunk)
    if not m:
        raise InputError(f"{what}: a row without the field {pattern.pattern.split(chr(34))[1]}")
    return m.group(1)


def check(files):
    stale = []
    for path in files:
        try:
            with open(path, encoding="utf-8") as f:
                text = f.read()
        except OSError as e:
            raise InputError(f"{path}: cannot read ({e.strerror})")
        for chunk in split_rows(text, path):
            claim_id = row_field(ROW_ID, chunk, path)
            if not claim_id.startswith("model."):
                continue
            budget = row_field(ROW_BUDGET, chunk, path)
            m = ROW_STAMP.search(chunk)
            want = expected_stamp(claim_id, budget)
            if not m:
                stale.append(f"{path}: {claim_id} ({budget}) carries no stamp")
            elif m.group(1) != want:
                stale.append(f"{path}: {claim_id} ({budget}) is stale: stamp {m.group(1)}, the "
                             f"current sources give {want}")
    for line in stale:
        print(line)
    if stale:
        print(f"{len(stale)} recorded conformance row(s) not produced by the current code; "
              "re-record them: /usr/bin/python3 scripts/row_stamps.py record --glintlab "
              "build/release/cli/glintlab --budget BUDGET --claims 'model.<name>.*' FILE")
    return 1 if stale else 0


def stamped(chunk, stamp):
    """`chunk` with its stamp field set to `stamp`, in the place of its sorted keys."""
    chunk = ROW_STAMP.sub("", chunk)
    m = re.search(r'^    "statistic": ', chunk, re.MULTILINE)
    if not m:
        raise InputError("a conformance row without the field statistic")
    return chunk[:m.start()] + f'    "stamp": "{stamp}",\n' + chunk[m.start():]


def run_verify(args):
    """The text of claims.json from `glintlab verify` with record's and reproduce's options."""
    with tempfile.TemporaryDirectory(prefix="row_stamps.") as tmp:
        cmd = [args.glintlab, "verify", "--budget", args.budget, "--claims", args.claims,
               "--out", os.path.join(tmp, "verify")]
        if args.threads is not None:
            cmd += ["--threads", str(args.threads)]
        run = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        # 1: a verdict differs from the recorded one — what re-recording is for.
        if run.returncode not in (0, 1):
            raise InputError(f"glintlab verify exited {run.returncode}: "
                             f"{run.stderr.strip().splitlines()[-1] if run.stderr.strip() else ''}")
        with open(os.path.join(tmp, "verify", "claims.json"), encoding="utf-8") as f:
            return f.read()


# Properties whose value and detail are measured times, different in every run.
TIMING_PROPERTIES = ("constant-time",)


def reproduce(args):
    with open(args.file, encoding="utf-8") as f:
        recorded = {r["id"]: r for r in json.loads(f.read())}
    fresh = [r for r in json.loads(run_verify(args)) if r["id"].startswith("model.")]
    if not fresh:
        raise InputError(f"--claims '{args.claims}': no conformance row was written")
    bad = 0
    for row in fresh:
        claim_id = row["id"]
        old = recorded.get(claim_id)
        if old is None:
            print(f"{claim_id}: not recorded in {args.file}")
            bad += 1
            continue
        if claim_id.rsplit(".", 1)[-1] in TIMING_PROPERTIES:
            keys = ("budget", "verdict", "control_verdict", "control_rejected")
        else:
            keys = sorted((set(row) | set(old)) - {"seconds", "stamp"})
        differ = [k for k in keys if row.get(k) != old.get(k)]
        if differ:
            bad += 1
            shown = ", ".join(f"{k}: {old.get(k)!r} -> {row.get(k)!r}"[:200] for k in differ)
            print(f"{claim_id}: {shown}")
    print(f"row_stamps: {len(fresh) - bad} of {len(fresh)} conformance row(s) of budget "
          f"{args.budget} reproduced from {args.file}")
    return 1 if bad else 0


def record(args):
    with open(args.file, encoding="utf-8") as f:
        text = f.read()
    base = split_rows(text, args.file)
    fresh = split_rows(run_verify(args), "verify's claims.json")
    # The first and last chunks carry the list's brackets: without them every row has one form.
    def inner(chunks):
        rows = list(chunks)
        rows[0] = rows[0][len("[\n  {"):]
        rows[-1] = rows[-1][:rows[-1].rstrip("\n").rfind("\n  }\n]")]
        return rows

    rows, new = inner(base), inner(fresh)
    index = {row_field(ROW_ID, r, args.file): i for i, r in enumerate(rows)}
    count = 0
    changed = []
    for chunk in new:
        claim_id = row_field(ROW_ID, chunk, "verify's claims.json")
        budget = row_field(ROW_BUDGET, chunk, "verify's claims.json")
        if budget != args.budget:
            raise InputError(f"{claim_id}: verify wrote budget {budget}, not {args.budget}")
        if claim_id.startswith("model."):
            chunk = stamped(chunk, expected_stamp(claim_id, budget))
        if claim_id in index:
            before = row_field(ROW_VERDICT, rows[index[claim_id]], args.file)
            after = row_field(ROW_VERDICT, chunk, "verify's claims.json")
            if before != after:
                changed.append(f"{claim_id}: {before} -> {after}")
            rows[index[claim_id]] = chunk
        else:
            index[claim_id] = len(rows)
            rows.append(chunk)
        count += 1
    if count == 0:
        raise InputError(f"--claims '{args.claims}': verify wrote no row")
    out = "[\n  {" + ROW_SEPARATOR.join(rows) + "\n  }\n]" + text[len(text.rstrip("\n")):]
    if not out.endswith("\n"):
        out += "\n"
    fd, tmp_path = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(args.file)),
                                    prefix=".row_stamps.")
    with os.fdopen(fd, "w", encoding="utf-8") as f:
        f.write(out)
    json.loads(out)  # still one valid list
    os.replace(tmp_path, args.file)
    print(f"row_stamps: {count} row(s) of budget {args.budget} recorded in {args.file}")
    for line in changed:
        print(f"row_stamps: verdict changed: {line}")
    return 0


def main(argv):
    global REPO
    parser = argparse.ArgumentParser(prog="row_stamps.py", description=__doc__.splitlines()[0])
    parser.add_argument("--source", default=REPO)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("check")
    p.add_argument("files", nargs="+")
    for name in ("record", "reproduce"):  # both run the suite: the same options
        p = sub.add_parser(name)
        p.add_argument("--glintlab", required=True)
        p.add_argument("--budget", required=True, choices=("quick", "full"))
        p.add_argument("--claims", default="model.*")
        p.add_argument("--threads", type=int)
        p.add_argument("file")
    p = sub.add_parser("files")
    p.add_argument("id")
    args = parser.parse_args(argv)
    REPO = args.source
    try:
        if not os.path.isdir(os.path.join(REPO, "core")):
            raise InputError(f"--source: '{REPO}' is not a glintlab source tree (no core/)")
        if args.command == "check":
            return check(args.files)
        if args.command == "record":
            return record(args)
        if args.command == "reproduce":
            return reproduce(args)
        for path in covered_files(args.id):
            print(path)
        return 0
    except (InputError, json.JSONDecodeError) as e:
        print(f"row_stamps: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
