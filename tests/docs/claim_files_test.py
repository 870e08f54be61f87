"""A claim is one short file: every file under verify/claims is at most 400 lines, so a researcher
auditing a claim reads one file (docs/architecture.md, "Add a claim"). The rule is tested on a
made-up tree first, so a check that can never fail would fail here. Usage: claim_files_test.py.
Exit 0 pass, 1 fail."""
import os
import sys
import tempfile

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
LIMIT = 400


def too_long(folder):
    """(path, lines) of every .cpp and .h under `folder` longer than LIMIT lines."""
    out = []
    for base, _, names in os.walk(folder):
        for name in sorted(names):
            if name.endswith((".cpp", ".h")):
                path = os.path.join(base, name)
                with open(path, encoding="utf-8") as f:
                    lines = sum(1 for _ in f)
                if lines > LIMIT:
                    out.append((os.path.relpath(path, folder), lines))
    return sorted(out)


def main():
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        os.makedirs(os.path.join(tmp, "paper"))
        for name, n in (("paper/at_limit.cpp", LIMIT), ("paper/over.cpp", LIMIT + 1),
                        ("notes.txt", 1000)):
            with open(os.path.join(tmp, name), "w", encoding="utf-8") as f:
                f.write("//\n" * n)
        if too_long(tmp) != [(os.path.join("paper", "over.cpp"), LIMIT + 1)]:
            failures.append(f"the rule itself: made-up tree gave {too_long(tmp)}")
    for path, lines in too_long(os.path.join(ROOT, "verify", "claims")):
        failures.append(f"verify/claims/{path}: {lines} lines (at most {LIMIT})")
    for f in failures:
        print(f"FAIL: {f}")
    print("claim files: " + ("FAIL" if failures else f"every file at most {LIMIT} lines"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
