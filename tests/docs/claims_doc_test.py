"""docs/claims.md is what scripts/claims_doc.py makes from the program's registry (glintlab verify
--list --json) and the recorded runs in docs/data: a claim added, a recorded verdict changed or a
run re-recorded without regenerating the page fails here. Also: a malformed registry is one line on
stderr, exit 2, nothing written. Usage: claims_doc_test.py GLINTLAB_EXE. Exit 0 pass, 1 fail."""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SCRIPT = os.path.join("scripts", "claims_doc.py")
RUNS = ["docs/data/claims-quick.json", "docs/data/claims-full.json"]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}")


def body(text):
    """The page without its first paragraph after the title (the command that made it)."""
    lines = text.split("\n")
    end = lines.index("", 2)
    return "\n".join(lines[:2] + lines[end:])


def doc(registry):
    return subprocess.run([sys.executable, SCRIPT, "--registry", registry] + RUNS, cwd=ROOT,
                          capture_output=True, text=True)


with tempfile.TemporaryDirectory() as tmp:
    registry = os.path.join(tmp, "registry.json")
    listed = subprocess.run([sys.argv[1], "verify", "--list", "--json"], capture_output=True,
                            text=True)
    check(listed.returncode == 0, f"verify --list --json: exit 0 (got {listed.returncode})")
    with open(registry, "w", encoding="utf-8") as f:
        f.write(listed.stdout)
    entries = json.loads(listed.stdout)
    r = doc(registry)
    check(r.returncode == 0, f"claims_doc: exit 0 (got {r.returncode}: {r.stderr.strip()})")
    with open(os.path.join(ROOT, "docs", "claims.md"), encoding="utf-8") as f:
        committed = f.read()
    check(body(r.stdout) == body(committed),
          "docs/claims.md is current: regenerate it with the command at its top")
    for e in entries:
        check(f"`{e['id']}`" in r.stdout, f"{e['id']} is in the page")
    # A run may report "error" (a check that could not run); a registry may not record it.
    run_with_error = os.path.join(tmp, "claims-error.json")
    some = entries[0]["id"]
    with open(run_with_error, "w", encoding="utf-8") as f:
        json.dump([{"id": some, "budget": "quick", "verdict": "error",
                    "detail": "claim x: exception: failed on purpose", "control": "none",
                    "control_rejected": False, "control_verdict": None, "value": 0,
                    "seconds": 0}], f)
    r = subprocess.run([sys.executable, SCRIPT, "--registry", registry, run_with_error],
                       cwd=ROOT, capture_output=True, text=True)
    check(r.returncode == 0 and "quick: none (**error**: the check could not run)" in r.stdout,
          f"a run's error verdict is accepted and shown (got {r.returncode}: {r.stderr.strip()})")
    recorded_error = os.path.join(tmp, "recorded-error.json")
    with open(recorded_error, "w", encoding="utf-8") as f:
        json.dump([dict(entries[0], expected_verdict={"quick": "error", "full": "error"})] +
                  entries[1:], f)
    r = subprocess.run([sys.executable, SCRIPT, "--registry", recorded_error] + RUNS, cwd=ROOT,
                       capture_output=True, text=True)
    check(r.returncode == 2 and "'error' is not a quick verdict" in r.stderr,
          f"error is never a recorded verdict (got {r.returncode}: {r.stderr.strip()})")
    # A malformed registry: an unknown verdict.
    bad = os.path.join(tmp, "bad.json")
    entries[0]["expected_verdict"]["quick"] = "holds-mostly"
    with open(bad, "w", encoding="utf-8") as f:
        json.dump(entries, f)
    out = os.path.join(tmp, "out.md")
    r = subprocess.run([sys.executable, SCRIPT, "--registry", bad, "--out", out] + RUNS,
                       cwd=ROOT, capture_output=True, text=True)
    check(r.returncode == 2 and len(r.stderr.strip().split("\n")) == 1 and
          "holds-mostly" in r.stderr, f"a malformed registry: one line, exit 2 (got {r.stderr!r})")
    check(not os.path.exists(out), "a malformed registry writes nothing")

print("claims doc tests " + ("FAILED" if failures else "passed"))
sys.exit(1 if failures else 0)
