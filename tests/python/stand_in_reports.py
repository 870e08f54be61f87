"""A reports folder whose figure_charts.py "draws" each chart as the bytes of its spec followed by
its CSV's (as CliTest::stand_in_charts does for the CLI tests, tests/cli/cli_test_util.cpp),
without matplotlib's start-up and drawing (about 0.1 s a map, 20 to 40 maps a quick sweep of one
model), and whose compare_page.py writes compare.json's bytes as the page, for
GLINTLAB_REPORTS_DIR. For runs whose files are compared or whose maps are not looked at, not
drawn: the same spec and data are the same PNG in any run, and the real drawing from Python is run
by slow_register_model_conformance.py (a sweep, the models-hemisphere figure and compare's page),
test_installed_package_uses_its_own_report_scripts (a sweep with the installed scripts) and
test_example_my_glint_model (compare's page)."""

import os
import shutil

STAND_IN_FIGURE_CHARTS = """import glob, os, sys
a = sys.argv
for i, d in enumerate(a):
    if i and a[i - 1] == '--dir':
        for spec in sorted(glob.glob(os.path.join(d, '*.chart.json'))):
            text = open(spec, 'rb').read()
            csv = text.split(b'"csv": "')[1].split(b'"')[0].decode()
            text += open(os.path.join(d, csv), 'rb').read()
            open(spec[:-len('.chart.json')] + '.png', 'wb').write(text)
"""

# compare's page (compare_page.py --dir DIR) is drawn from DIR/compare.json alone: the stand-in's
# index.html and equal_time.png are its bytes.
STAND_IN_COMPARE_PAGE = """import os, sys
d = sys.argv[sys.argv.index('--dir') + 1]
text = open(os.path.join(d, 'compare.json'), 'rb').read()
for page in ('equal_time.png', 'index.html'):
    open(os.path.join(d, page), 'wb').write(text)
"""

REPORTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "reports")


def stand_in_reports(folder, with_pages=False):
    """`folder` with the stand-in figure_charts.py and compare_page.py in it; with_pages: the
    other report scripts copied beside the stand-in figure_charts.py instead (compare's page
    drawn by the real compare_page.py)."""
    if with_pages:
        shutil.copytree(REPORTS, folder, dirs_exist_ok=True,
                        ignore=shutil.ignore_patterns("__pycache__"))
    else:
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, "compare_page.py"), "w") as f:
            f.write(STAND_IN_COMPARE_PAGE)
    with open(os.path.join(folder, "figure_charts.py"), "w") as f:
        f.write(STAND_IN_FIGURE_CHARTS)
    return folder
