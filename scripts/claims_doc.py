#!/usr/bin/python3
"""Writes docs/claims.md: one table of every registered claim of `glintlab verify`.

Usage (Debian's /usr/bin/python3, standard library only):

    glintlab verify --list --json > REGISTRY
    /usr/bin/python3 scripts/claims_doc.py --registry REGISTRY [CLAIMS_JSON ...] [--out FILE]

Each CLAIMS_JSON is the claims.json that `glintlab verify --out DIR [--budget quick|full]`
writes (a list of records; each record names its budget). Give the quick and the full run's
files to fill both verdict columns. The registered claims and their recorded verdicts (what
`glintlab verify` must reproduce for its exit status 0) come from the program itself, the JSON
of `glintlab verify --list --json`, in the registry's order; with no CLAIMS_JSON the table shows
only those, and its header says so. Without --out the Markdown goes to stdout. A malformed input is one line on
stderr, exit status 2, and nothing written.
"""

import argparse
import json
import os
import sys
import tempfile
import textwrap

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# A run may also report "error" (the check could not compute its statistic); no claim records it.
RECORDED_VERDICTS = ("holds", "holds-within", "holds-in-regime", "fails", "inconclusive",
                     "not-claimed")
VERDICTS = RECORDED_VERDICTS + ("error",)
BUDGETS = ("quick", "full")

# One line per registered claim: what the paper says, in this project's words (the ids are those
# of the project's claims catalogue). A claim missing here is printed with an empty statement.
STATEMENTS = {
    "smooth.projected-area": "the projected area of the GGX and Beckmann NDFs is 1",
    "smooth.vndf-normalized": "the visible-normal distribution integrates to 1 for every ωi",
    "smooth.sampler-matches-pdf": "every smooth sampler draws from the pdf it reports",
    "smooth.eval-pdf-consistency": "weight = eval·cos/pdf and pdf(sample()) = pdf(ωo)",
    "eto.pdf-matches": "the bounded sampler's directions follow its pdf (Eq. 8, Listing 2)",
    "eto.unbiased": "estimates with the bounded sampler are unbiased",
    "eto.bound-is-infimum": "the isotropic bound −k·i_z is the infimum of o_z (Eq. 5)",
    "eto.fewer-rejections": "bounded caps reject fewer samples (half at α = 1, θi = 0 before)",
    "eto.variance-rough": "lower RMSE at equal samples for rough, low-anisotropy surfaces",
    "eto.variance-smooth": "no material RMSE difference at low roughness (α = 0.2)",
    "eto.backfacing-stable-pdf": "the stable back-facing pdf equals Eq. 7",
    "kemppinen.jacobian": "|J_T| = D/|U_Ω| for the GGX and Beckmann maps (Eq. 3)",
    "kemppinen.convergence": "the area mean of D★ converges to D (Eq. 2)",
    "kemppinen.compensation": "with k = 4, Eq. 11 matches the brute-force Eq. 5 in most cases (Eq. 9–11)",
    "kemppinen.compensation-k16": "where k = 4 brightens (lobe at the rim of U_Ω), k = 16 mitigates (Fig. 14)",
    "kemppinen.roulette": "roulette MIP blending equals linear blending in expectation (Eq. 8)",
    "kemppinen.furnace": "averaged over area the glinty NDF gains no energy (Fig. 15)",
    "kemppinen.constant-time": "evaluation cost does not grow with footprint, LOD or anisotropy",
    "kemppinen.sampling-unbiased": "Algorithm 2 samples D★^f without bias (Fig. 7)",
    "kneiphof.total-area": "Eq. 29/30 equal the total microfacet area; Eq. 31 approximates Eq. 30",
    "kneiphof.discrete-ndf-mean": "the discrete NDF has mean D (App. A)",
    "kneiphof.subdivision": "splitting the light leaves the counts and radiance unchanged (App. C)",
    "kneiphof.convergence": "the glint estimate converges to L_o as N_P grows (Fig. 10)",
    "kneiphof.cap-probability": "the cap probability of Eq. 20 is valid only in a regime",
    "kneiphof.ltc-probability": "the BRDF LTC lobe × D_PR as D_Ωh looks the same (Sec. 7, Fig. 8)",
    "chermain.kernel-normalized": "filtered marginals stay normalised, so GGAA keeps energy",
    "chermain.dictionary-converges": "dictionary levels converge to a Gaussian of std σ_o",
    "chermain.correlation": "the matrix M of Eq. 18 gives the slope correlation ρ",
    "chermain.ggaa-error": "GGAA lowers the error on curved surfaces (Figs. 8–9)",
    "chermain.ggaa-derivatives": "projected-half-vector derivatives beat half-slope ones (Fig. 8)",
    "chermain.ggaa-sk": "s_K = 0.5 beats s_K = 1 in RMSE (Fig. 9)",
    "chermain.ggaa-shimmer": "s_K = 0.5 shimmers more than s_K = 1 (Fig. 9)",
    "chermain.lean-correlation": "LEAN with ρ beats LEAN with ρ = 0 and no LEAN (Fig. 7)",
    "podee.brightest-vector": "the chosen reflection vector is the pixel's brightest",
    "podee.rmse": "lower RMSE than centre sampling and LEAN (Table 1)",
    "podee.far-failure": "the method fails when a pixel holds much normal variation",
    "podee.stability": "less flicker than centre sampling under sub-pixel motion",
    "all.stability": "no registered model gives NaN, Inf or negative values in its core domain",
    "all.energy-gain": "no registered model gains energy (white furnace) in its core domain",
    "all.probability": "no registered model's probability exceeds 1 in its core domain",
    "all.variance": "no registered model's sample weights blow up at a fixed surface position (Var/E² > 81.92) in its core domain",
}


class InputError(Exception):
    pass


# ---- the recorded verdicts, from the program's registry ---------------------------------------

def read_registry(path):
    """The papers' claims and glintlab's rules in the registry's order, with their recorded
    verdicts: the JSON of `glintlab verify --list --json` (the program's own metadata; the C++
    sources are not parsed)."""
    try:
        with open(path, encoding="utf-8") as f:
            entries = json.load(f)
    except OSError as e:
        raise InputError(f"--registry: {e.strerror}: {path}")
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise InputError(f"--registry: {path} is not JSON ({e})")
    if not isinstance(entries, list) or not entries:
        raise InputError(f"--registry: {path}: expected the non-empty list that "
                         "glintlab verify --list --json prints")
    checks = []
    for i, e in enumerate(entries):
        if not isinstance(e, dict) or not isinstance(e.get("id"), str) or \
                not isinstance(e.get("expected_verdict"), dict):
            raise InputError(f"--registry: {path}: entry {i} lacks 'id' or 'expected_verdict'")
        if e.get("family"):
            continue  # a model's conformance check: taken from the runs (conformance_checks)
        recorded = {b: e["expected_verdict"].get(b) for b in BUDGETS}
        for b, v in recorded.items():
            if v not in RECORDED_VERDICTS:
                raise InputError(f"--registry: {path}: {e['id']}: '{v}' is not a {b} verdict")
        checks.append({"id": e["id"], "paper": e.get("paper", ""), "source": e.get("source", ""),
                       "recorded": recorded, "statistical": bool(e.get("statistical"))})
    ids = [c["id"] for c in checks]
    if len(set(ids)) != len(ids):
        raise InputError(f"--registry: {path}: a claim id appears twice")
    return checks


# ---- measured verdicts, from claims.json ---------------------------------------------------

def read_claims_json(path):
    try:
        with open(path, encoding="utf-8") as f:
            records = json.load(f)
    except OSError as e:
        raise InputError(f"{path}: {e.strerror}")
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise InputError(f"{path}: not JSON ({e})")
    if not isinstance(records, list) or not records:
        raise InputError(f"{path}: expected a non-empty list of claim records")
    runs = {}
    for i, r in enumerate(records):
        if not isinstance(r, dict):
            raise InputError(f"{path}: record {i} is not an object")
        for key, kind in (("id", str), ("verdict", str), ("budget", str),
                          ("control_rejected", bool)):
            if not isinstance(r.get(key), kind):
                raise InputError(f"{path}: record {i} lacks '{key}' ({kind.__name__})")
        if r["budget"] not in BUDGETS:
            raise InputError(f"{path}: record {i}: budget '{r['budget']}' is not quick or full")
        if r["verdict"] not in VERDICTS:
            raise InputError(f"{path}: record {i}: '{r['verdict']}' is not a verdict")
        runs.setdefault(r["budget"], {})[r["id"]] = r
    return runs


def conformance_checks(measured):
    """The model conformance checks (model.<name>.<property>) of the runs: generated from the
    model registry at run time and selected only by naming them; each run reports its
    recorded verdict (verify/conformance/conformance.cpp) as expected_verdict."""
    checks = {}
    for budget in BUDGETS:
        for cid, r in measured.get(budget, {}).items():
            if not cid.startswith("model."):
                continue
            c = checks.setdefault(cid, {
                "id": cid, "paper": r.get("paper", ""), "source": r.get("source", ""),
                "recorded": {}, "statistical": bool(r.get("raw_p_values"))})
            c["recorded"][budget] = r.get("expected_verdict", r["verdict"])
    for c in checks.values():
        for budget in BUDGETS:
            c["recorded"].setdefault(budget, c["recorded"].get("quick") or
                                     c["recorded"].get("full"))
    return sorted(checks.values(), key=lambda c: c["id"])


# ---- the document ----------------------------------------------------------------------------

def cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def verdict_cell(check, measured, budget):
    recorded = check["recorded"][budget]
    run = measured.get(budget, {}).get(check["id"])
    if run is None:
        if not measured:
            return recorded
        return f"{recorded} (recorded)" if measured.get(budget) is None else "not run"
    if run["verdict"] == recorded:
        return run["verdict"]
    return f"**{run['verdict']}** (recorded: {recorded})"


def control_cell(check, measured):
    """The control's own verdict per budget, and whether it opposes the claim's."""
    parts = []
    for budget in BUDGETS:
        run = measured.get(budget, {}).get(check["id"])
        if run is not None and run["verdict"] == "not-claimed":
            parts.append(f"{budget}: none (not claimed)")
        elif run is not None and run["verdict"] == "error":
            parts.append(f"{budget}: none (**error**: the check could not run)")
        elif run is not None:
            verdict = run.get("control_verdict")
            opposed = "opposes" if run["control_rejected"] else "**does NOT oppose**"
            parts.append(f"{budget}: {verdict} ({opposed})" if verdict else
                         f"{budget}: " + ("rejected" if run["control_rejected"] else "**NOT rejected**"))
    return "; ".join(parts) if parts else "—"


def regime_lines(checks, measured):
    """The declared regime of every claim that holds only in one, per budget."""
    lines = []
    for c in checks:
        for budget in BUDGETS:
            run = measured.get(budget, {}).get(c["id"])
            if run is not None and run.get("regime"):
                lines.append(f"- `{c['id']}` ({budget}): {run['regime']}")
    return lines


def budget_note_lines(checks, measured):
    """Why a claim's quick and full recorded verdicts differ, as its check's run says."""
    lines = []
    for c in checks:
        for budget in BUDGETS:
            run = measured.get(budget, {}).get(c["id"])
            if run is not None and run.get("budget_note"):
                lines.append(f"- `{c['id']}`: {run['budget_note']}")
                break
    return lines


def run_of(check, measured):
    """The claim's row of the quick run, else of the full run."""
    for budget in BUDGETS:
        run = measured.get(budget, {}).get(check["id"])
        if run is not None:
            return run
    return None


def finding_lines(checks, measured):
    """The papers' claims that fail (findings, every competing cause excluded) and those measured
    as failing whose competing causes are not all excluded (reported inconclusive), once per
    claim with the budgets it happened at."""
    lines = []
    for c in checks:
        runs = [(b, measured[b][c["id"]]) for b in BUDGETS if c["id"] in measured.get(b, {})]
        fails = [(b, r) for b, r in runs if r["verdict"] == "fails" and
                 r.get("kind") == "paper's claim"]
        open_ = [(b, r) for b, r in runs if r.get("measured_verdict") == "fails"]
        if fails:
            run = fails[-1][1]
            how = "; ".join(f"{a['cause']}: {a['how']}" for a in run.get("alternatives_excluded") or [])
            fix = f" Smallest correction: {run['correction']}" if run.get("correction") else ""
            lines.append(f"- `{c['id']}` fails ({', '.join(b for b, _ in fails)}): the paper: "
                         f"{run.get('paper_quote')} Competing causes excluded: {how}.{fix}")
        elif open_:
            run = open_[-1][1]
            why = "; ".join(f"{a['cause']}: {a['why']}" for a in run.get("alternatives_open") or [])
            lines.append(f"- `{c['id']}` measured as failing ({', '.join(b for b, _ in open_)}), "
                         f"reported inconclusive: {why or 'no competing cause reviewed'}")
    return lines


def quote_lines(checks, measured):
    """Every claim's paper sentence, and what the check tests beyond it."""
    lines = []
    for c in checks:
        run = run_of(c, measured)
        # A conformance row's quote restates its property, already in the table's statement.
        if run is None or not run.get("paper_quote") or run.get("kind") == "conformance":
            continue
        line = f"- `{c['id']}`: {run['paper_quote']}"
        if run.get("stronger_reading"):
            line += f" *Tested beyond the sentence:* {run['stronger_reading']}"
        lines.append(line)
    return lines


def render(checks, measured, command, inputs):
    lines = [
        "# Claims and verdicts",
        "",
        f"Generated by `{command}`; do not edit by hand.",
        "",
    ]
    if measured:
        described = ", ".join(f"`{p}` ({b})" for p, b in inputs)
        lines.append(f"Measured verdicts from {described}.")
    else:
        lines.append(
            "No claims.json was given: every verdict below is the one recorded in the registry "
            "(`glintlab verify --list --json`), which `glintlab verify` must reproduce (exit "
            "status 0), not a measurement. The control column needs a claims.json: `glintlab verify` "
            "exits 1 when a negative control is not rejected.")
    missing = [b for b in BUDGETS if b not in measured]
    if measured and missing:
        lines.append(
            f"No {' or '.join(missing)}-budget claims.json was given: that column shows the "
            "verdict recorded in the registry, marked \"(recorded)\".")
    statistical = sum(1 for c in checks if c["statistical"])
    lines += [
        "",
        f"{len(checks)} registered claims: {statistical} statistical (a p-value, with a "
        f"calibration run by `glintlab verify --calibrate ID`) and {len(checks) - statistical} "
        "decided otherwise (an error bound, an interval against a tolerance, or an exact "
        "recomputation). Each has a control that its own decision must give the opposite "
        "verdict. How the suite works: [verification.md](verification.md); the evidence "
        "per paper, beside the paper's numbers: [papers/](papers/README.md).",
        "",
    ]
    for budget in BUDGETS:
        runs = measured.get(budget)
        if not runs:
            continue
        ran = [c for c in checks if c["id"] in runs]
        same = sum(1 for c in ran if runs[c["id"]]["verdict"] == c["recorded"][budget])
        rejected = sum(1 for c in ran if runs[c["id"]]["control_rejected"] or
                       runs[c["id"]]["verdict"] == "not-claimed")
        lines.append(f"- {budget} budget: {len(ran)} of {len(checks)} claims run, {same} as "
                     f"recorded, {rejected} of {len(ran)} negative controls rejected.")
        unknown = sorted(set(runs) - {c["id"] for c in checks})
        if unknown:
            lines.append(f"  Not in the registry: {', '.join(unknown)}.")
    if measured:
        lines.append("")
    lines += [
        "| claim | paper | source | statement | kind | quick | full | control |",
        "| --- | --- | --- | --- | --- | --- | --- | --- |",
    ]
    for c in checks:
        lines.append("| " + " | ".join(cell(x) for x in (
            f"`{c['id']}`", c["paper"], c["source"], STATEMENTS.get(c["id"], ""),
            "statistical" if c["statistical"] else "bound or interval",
            verdict_cell(c, measured, "quick"), verdict_cell(c, measured, "full"),
            control_cell(c, measured))) + " |")
    regimes = regime_lines(checks, measured)
    if regimes:
        lines += ["", "Regimes, as each check declares them in its code before measuring:", ""]
        lines += regimes
    findings = finding_lines(checks, measured)
    if findings:
        lines += ["", "Failures and their competing causes (a paper's claim fails only when every "
                  "other cause — our bug, our scene or reference, our convention, our tolerance — "
                  "is excluded; otherwise it is inconclusive):", ""]
        lines += findings
    quotes = quote_lines(checks, measured)
    if quotes:
        lines += ["", "What each claim is judged against, in the paper's words:", ""]
        lines += quotes
    notes = budget_note_lines(checks, measured)
    if notes:
        lines += ["", "Where the two budgets record different verdicts, and why:", ""]
        lines += notes
    lines += [
        "",
        "Verdicts: **holds**; **holds-within** (within a stated tolerance); **holds-in-regime** "
        "(inside a parameter region the check declares before measuring, listed above; the "
        "detail says what happens outside); **fails** (with the evidence); **inconclusive** "
        "(the test could not decide, e.g. an interval straddling the tolerance); **not-claimed** "
        "(model conformance only: a property the model declares it does not claim, with the "
        "reason; nothing is measured); **error** (a run's check could not compute its statistic: "
        "an exception, e.g. from a plug-in's eval, or NaN where a number is required; the detail "
        "names the model and the cause; never a recorded verdict). The control "
        "column gives the verdict the same measurement and decision reach on the control's "
        "input: a deliberately wrong input for a claim that holds (it must fail), the corrected "
        "formula or input for a claim that fails (it must hold). A verdict that differs from the "
        "recorded one is a regression or a finding.",
        "",
    ]
    return "\n".join(wrap(line) for line in lines)


def wrap(line):
    """Prose lines wrapped at 100 characters; table rows and list items left as they are."""
    if line.startswith(("|", "#", "- ", "  ")) or len(line) <= 100:
        return line
    return textwrap.fill(line, width=100, break_long_words=False, break_on_hyphens=False)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("claims_json", nargs="*", help="claims.json of glintlab verify runs")
    parser.add_argument("--out", help="Markdown file to write (default: stdout)")
    parser.add_argument("--registry", required=True,
                        help="the JSON that glintlab verify --list --json prints")
    args = parser.parse_args(argv)
    try:
        checks = read_registry(args.registry)
        measured, inputs = {}, []
        for path in args.claims_json:
            for budget, runs in read_claims_json(path).items():
                if budget in measured:
                    raise InputError(f"{path}: a second {budget}-budget run was given")
                measured[budget] = runs
                inputs.append((path, budget))
        checks += conformance_checks(measured)
        command = (f"glintlab verify --list --json > {args.registry}; " + " ".join(
            ["/usr/bin/python3 scripts/claims_doc.py", "--registry", args.registry] +
            args.claims_json + (["--out", args.out] if args.out else [])))
        text = render(checks, measured, command, inputs)
        if args.out:
            folder = os.path.dirname(os.path.abspath(args.out))
            if not os.path.isdir(folder):
                raise InputError(f"--out: no folder '{folder}'")
            fd, tmp = tempfile.mkstemp(dir=folder, prefix=".claims_doc.")
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                f.write(text)
            os.replace(tmp, args.out)
        else:
            sys.stdout.write(text)
    except InputError as e:
        print(f"claims_doc: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
