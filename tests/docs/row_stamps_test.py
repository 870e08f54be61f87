"""scripts/row_stamps.py: a conformance row's stamp follows the files it covers and no others; `check`
passes a row stamped from the current sources and fails a stale or unstamped one; `record` puts
stamped rows from a verify run into a claims file, every other row byte for byte; bad input is one
line on stderr, exit 2, nothing written. Usage: row_stamps_test.py. Exit 0 pass, 1 fail."""
import json
import os
import shutil
import stat
import subprocess
import sys
import tempfile

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
SCRIPT = os.path.join(ROOT, "scripts", "row_stamps.py")
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}")


def stamps(source, *args):
    return subprocess.run([sys.executable, SCRIPT, "--source", source] + list(args),
                          capture_output=True, text=True)


def row(claim_id, budget, verdict="holds", stamp=None):
    """One row as glintlab verify writes it (keys sorted, two spaces of indent)."""
    fields = {"budget": budget, "id": claim_id, "statistic": "s", "verdict": verdict}
    if stamp:
        fields["stamp"] = stamp
    return json.dumps(fields, indent=2, sort_keys=True, ensure_ascii=False)


def claims_file(rows):
    return json.dumps([json.loads(r) for r in rows], indent=2, sort_keys=True,
                      ensure_ascii=False) + "\n"


def expected(source, claim_id, budget):
    """The stamp `record` gives, read back from a file it wrote."""
    with tempfile.TemporaryDirectory() as tmp:
        fake = os.path.join(tmp, "glintlab")
        write_fake_glintlab(fake, [row(claim_id, budget)])
        target = os.path.join(tmp, "claims.json")
        with open(target, "w", encoding="utf-8") as f:
            f.write(claims_file([row("smooth.projected-area", budget)]))
        r = stamps(source, "record", "--glintlab", fake, "--budget", budget, "--claims", claim_id,
                   target)
        check(r.returncode == 0, f"record {claim_id}: exit 0 (got {r.returncode}: {r.stderr})")
        with open(target, encoding="utf-8") as f:
            return {x["id"]: x.get("stamp") for x in json.load(f)}[claim_id]


def write_fake_glintlab(path, rows, exit_code=1):
    """A stand-in for glintlab verify: writes `rows` as DIR/claims.json (--out DIR), exits
    `exit_code` (1: a verdict differs from the recorded one)."""
    with open(path, "w", encoding="utf-8") as f:
        f.write("#!/usr/bin/python3\nimport os, sys\n"
                "out = sys.argv[sys.argv.index('--out') + 1]\n"
                "os.makedirs(out)\n"
                f"open(os.path.join(out, 'claims.json'), 'w', encoding='utf-8').write({claims_file(rows)!r})\n"
                f"sys.exit({exit_code})\n")
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)


with tempfile.TemporaryDirectory() as tmp:
    # A copy of the sources, to change a file without touching the repository.
    src = os.path.join(tmp, "src")
    for folder in ("core", "verify", "cli"):
        shutil.copytree(os.path.join(ROOT, folder), os.path.join(src, folder))

    # The covered files: the model's own header and the suite's code, not another model's header.
    files = stamps(src, "files", "model.smooth_ggx.energy").stdout.split()
    check("core/models/smooth_ggx.h" in files, "smooth_ggx's stamp covers its header")
    check("verify/conformance/sampling.cpp" in files, "the stamp covers the suite's code")
    check("core/simd/isa_avx2.cpp" in files, "the stamp covers the ISA units")
    check("core/models/kemppinen_ggx.h" not in files,
          "smooth_ggx's stamp does not cover another model's header")
    check("core/model_list.h" in files, "core/model_list.h is covered (hashed, not followed)")

    ggx_quick = expected(src, "model.smooth_ggx.energy", "quick")
    ggx_full = expected(src, "model.smooth_ggx.energy", "full")
    podee = expected(src, "model.podee.energy", "quick")
    check(ggx_quick and ggx_quick.startswith("sha256:"), f"a stamp is written ({ggx_quick})")
    check(ggx_quick != ggx_full, "the budget is part of the stamp")
    check(ggx_quick != expected(src, "model.smooth_ggx.stability", "quick"),
          "the claim id is part of the stamp")

    target = os.path.join(tmp, "recorded.json")
    with open(target, "w", encoding="utf-8") as f:
        f.write(claims_file([row("smooth.projected-area", "quick"),
                             row("model.smooth_ggx.energy", "quick", stamp=ggx_quick),
                             row("model.podee.energy", "quick", stamp=podee)]))
    r = stamps(src, "check", target)
    check(r.returncode == 0, f"check passes rows stamped from these sources ({r.stdout})")

    # A change to the model's header makes its rows stale, and only its rows.
    header = os.path.join(src, "core", "models", "smooth_ggx.h")
    with open(header, "a", encoding="utf-8") as f:
        f.write("// changed\n")
    r = stamps(src, "check", target)
    check(r.returncode == 1, f"check fails after the model's header changed (got {r.returncode})")
    check("model.smooth_ggx.energy (quick) is stale" in r.stdout, f"the stale row is named: {r.stdout}")
    check("model.podee" not in r.stdout, f"another model's row stays current: {r.stdout}")
    check(expected(src, "model.podee.energy", "quick") == podee,
          "another model's stamp does not change")

    # A change to the suite's code makes every conformance row stale.
    with open(os.path.join(src, "verify", "stats", "chi_square.cpp"), "a", encoding="utf-8") as f:
        f.write("// changed\n")
    r = stamps(src, "check", target)
    check("model.podee.energy (quick) is stale" in r.stdout,
          f"a change to a statistics file the suite calls stales every model: {r.stdout}")

    # An unstamped conformance row fails; a paper claim's row needs none.
    with open(target, "w", encoding="utf-8") as f:
        f.write(claims_file([row("smooth.projected-area", "quick"),
                             row("model.podee.energy", "quick")]))
    r = stamps(src, "check", target)
    check(r.returncode == 1 and "model.podee.energy (quick) carries no stamp" in r.stdout,
          f"an unstamped row fails: {r.returncode} {r.stdout}")

    # record: replaces the row with its id, appends a new one, leaves the others byte for byte.
    other = row("smooth.projected-area", "quick", verdict="fails")
    with open(target, "w", encoding="utf-8") as f:
        f.write(claims_file([other, row("model.podee.energy", "quick", verdict="fails")]))
    with open(target, encoding="utf-8") as f:
        before = f.read()
    fake = os.path.join(tmp, "glintlab")
    write_fake_glintlab(fake, [row("model.podee.energy", "quick"),
                               row("model.podee.stability", "quick")])
    r = stamps(src, "record", "--glintlab", fake, "--budget", "quick", "--claims", "model.podee.*",
               target)
    check(r.returncode == 0, f"record: exit 0 ({r.stderr})")
    with open(target, encoding="utf-8") as f:
        after = f.read()
    rows = json.loads(after)
    check([x["id"] for x in rows] == ["smooth.projected-area", "model.podee.energy",
                                      "model.podee.stability"],
          f"record replaced one row and appended one: {[x['id'] for x in rows]}")
    check(rows[1]["verdict"] == "holds", "the replaced row is the new run's")
    check("verdict changed: model.podee.energy: fails -> holds" in r.stdout,
          f"record names the changed verdict: {r.stdout}")
    check(after.startswith(before[:before.index('  },')]), "the other row is kept byte for byte")
    check(all("stamp" in x for x in rows[1:]), "recorded rows carry stamps")
    check(after == claims_file(json.dumps(x, indent=2, sort_keys=True, ensure_ascii=False)
                               for x in rows),
          "the file keeps the form glintlab verify writes (sorted keys, two spaces)")
    r = stamps(src, "check", target)
    check(r.returncode == 0, f"what record wrote passes check ({r.stdout})")

    # A paper claim's row is recorded as verify wrote it, without a stamp.
    write_fake_glintlab(fake, [row("smooth.projected-area", "quick", verdict="holds")])
    r = stamps(src, "record", "--glintlab", fake, "--budget", "quick", "--claims",
               "smooth.projected-area", target)
    with open(target, encoding="utf-8") as f:
        paper = json.loads(f.read())
    check(r.returncode == 0 and paper[0]["verdict"] == "holds" and "stamp" not in paper[0]
          and [x["id"] for x in paper] == [x["id"] for x in rows],
          f"a paper claim's row replaced, unstamped: {r.returncode} {r.stderr}")
    r = stamps(src, "check", target)
    check(r.returncode == 0, f"and check still passes ({r.stdout})")

    # Replacing the first and the last row keeps the form too.
    write_fake_glintlab(fake, [row("model.podee.stability", "quick", verdict="fails")])
    with open(target, "w", encoding="utf-8") as f:
        f.write(claims_file([row("model.podee.stability", "quick"), other]))
    r = stamps(src, "record", "--glintlab", fake, "--budget", "quick", target)
    with open(target, encoding="utf-8") as f:
        first = f.read()
    check(r.returncode == 0 and json.loads(first)[0]["verdict"] == "fails"
          and first == claims_file(json.dumps(x, indent=2, sort_keys=True, ensure_ascii=False)
                                   for x in json.loads(first)),
          f"the first row replaced in place: {first}")
    with open(target, "w", encoding="utf-8") as f:
        f.write(after)

    # Bad input: one line on stderr, exit 2, the file unchanged.
    write_fake_glintlab(fake, [row("model.podee.energy", "quick")], exit_code=2)
    r = stamps(src, "record", "--glintlab", fake, "--budget", "quick", target)
    check(r.returncode == 2 and r.stderr.startswith("row_stamps: error: glintlab verify exited 2")
          and r.stderr.count("\n") == 1, f"a failed verify run: {r.returncode} {r.stderr!r}")
    with open(target, encoding="utf-8") as f:
        check(f.read() == after, "a failed record leaves the file as it was")
    with open(os.path.join(tmp, "bad.json"), "w", encoding="utf-8") as f:
        f.write("{\"id\": 1}\n")
    r = stamps(src, "check", os.path.join(tmp, "bad.json"))
    check(r.returncode == 2 and "not a claims file" in r.stderr, f"a malformed file: {r.stderr!r}")
    r = stamps(src, "files", "smooth.projected-area")
    check(r.returncode == 2 and "not a conformance claim" in r.stderr, f"a paper claim: {r.stderr!r}")
    r = stamps(src, "files", "model.no_such_model.energy")
    check(r.returncode == 2 and "no_such_model" in r.stderr, f"an unknown model: {r.stderr!r}")

    # reproduce: every field of each row verify writes equals the recorded row's, but seconds and
    # stamp; a timing property's verdicts only; the file is left as it is.
    def full_row(claim_id, value, seconds=1.0, detail="d", verdict="holds"):
        return json.dumps({"budget": "quick", "id": claim_id, "statistic": "s", "value": value,
                           "detail": detail, "seconds": seconds, "verdict": verdict},
                          indent=2, sort_keys=True, ensure_ascii=False)

    recorded = os.path.join(tmp, "reproduce.json")
    with open(recorded, "w", encoding="utf-8") as f:
        f.write(claims_file([row("smooth.projected-area", "quick"),
                             full_row("model.podee.energy", 0.5),
                             full_row("model.podee.constant-time", 1.02, detail="0.3 us")]))
    with open(recorded, encoding="utf-8") as f:
        kept = f.read()

    def reproduce(rows):
        write_fake_glintlab(fake, rows, exit_code=0)
        return stamps(src, "reproduce", "--glintlab", fake, "--budget", "quick", recorded)

    r = reproduce([full_row("model.podee.energy", 0.5, seconds=9.0),
                   full_row("model.podee.constant-time", 0.97, seconds=3.0, detail="0.31 us")])
    check(r.returncode == 0 and "2 of 2 conformance row(s)" in r.stdout,
          f"reproduce: other seconds and another measured time pass: {r.returncode} {r.stdout}")
    r = reproduce([full_row("model.podee.energy", 0.5 * 1.03),
                   full_row("model.podee.constant-time", 1.02, detail="0.3 us")])
    check(r.returncode == 1 and "model.podee.energy: value: 0.5 -> 0.515" in r.stdout
          and "1 of 2" in r.stdout, f"reproduce: a value 3 % off fails, named: {r.stdout}")
    r = reproduce([full_row("model.podee.energy", 0.5),
                   full_row("model.podee.constant-time", 1.02, verdict="fails")])
    check(r.returncode == 1 and "model.podee.constant-time: verdict" in r.stdout,
          f"reproduce: a timing property's verdict is compared: {r.stdout}")
    r = reproduce([full_row("model.podee.energy", 0.5, detail="other")])
    check(r.returncode == 1 and "model.podee.energy: detail" in r.stdout,
          f"reproduce: a detail that differs fails: {r.stdout}")
    r = reproduce([full_row("model.podee.stability", 0.5)])
    check(r.returncode == 1 and "model.podee.stability: not recorded" in r.stdout,
          f"reproduce: a row the file lacks fails: {r.stdout}")
    with open(recorded, encoding="utf-8") as f:
        check(f.read() == kept, "reproduce leaves the file as it was")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
