"""After scripts/install.sh (run by scripts/test.sh and scripts/main.sh, which then set
GLINTLAB_INSTALLED_PREFIX): Debian's /usr/bin/python3 imports `glintlab` without PYTHONPATH, from
that prefix, and it is this build's package; the examples run against it. Without
GLINTLAB_INSTALLED_PREFIX (a plain `ctest` in a build tree that was not installed) it is skipped.
Usage: installed_package_test.py BUILD_PYTHON_DIR. Exit 0 pass, 1 fail, 77 skipped."""
import filecmp
import os
import subprocess
import sys
import tempfile

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
prefix = os.environ.get("GLINTLAB_INSTALLED_PREFIX")
if not prefix:
    print("skipped: GLINTLAB_INSTALLED_PREFIX is not set (scripts/test.sh sets it after "
          "scripts/install.sh)")
    sys.exit(77)

build_package = os.path.join(sys.argv[1], "glintlab")
env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
env["MPLBACKEND"] = "Agg"
failures = []


def python(args, cwd):
    return subprocess.run(["/usr/bin/python3"] + args, cwd=cwd, env=env, capture_output=True,
                          text=True)


with tempfile.TemporaryDirectory() as tmp:
    r = python(["-c", "import glintlab; print(glintlab.__file__)"], tmp)
    where = r.stdout.strip()
    if r.returncode != 0 or not where.startswith(os.path.join(prefix, "")):
        failures.append(f"import glintlab without PYTHONPATH: exit {r.returncode}, from '{where}' "
                        f"(expected below {prefix}) {r.stderr.strip()}")
    else:
        installed = os.path.dirname(where)
        for name in sorted(os.listdir(build_package)):
            if name.endswith((".py", ".so")) and not filecmp.cmp(
                    os.path.join(build_package, name), os.path.join(installed, name),
                    shallow=False):
                failures.append(f"{installed}/{name} is not this build's (install again)")
    # The example compares smooth_beckmann, whose stability maps (which it sweeps, drawn by
    # matplotlib with the installed report scripts) are 20, smooth_ggx's 40.
    for script, args in (("lobes.py", [os.path.join(tmp, "lobes.png")]),
                         ("my_glint_model.py", ["--out", os.path.join(tmp, "glint.png"),
                                                "--properties", "eval-pdf-consistency",
                                                "--compare-with", "smooth_beckmann",
                                                "--compare-papers-only"])):
        r = python([os.path.join(ROOT, "examples", "python", script)] + args, tmp)
        if r.returncode != 0:
            failures.append(f"examples/python/{script} against the installed package: exit "
                            f"{r.returncode}: {r.stderr.strip()[-400:]}")

for f in failures:
    print(f"FAIL: {f}")
print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
