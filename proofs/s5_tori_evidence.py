r"""Section 5's qualitative dynamics as numerical evidence: S5:EJ-tori,
S5:reconstruction and Th:Re-tori:frequencies, each on at least 200 drawn orbits.

No identity can decide these statements; a measurement can support them, and a control shows
that the measurement could have come out otherwise. Verdict ``evidence`` (never ``holds``), or
``open`` with the numbers. Every row rests on initial conditions drawn by the ledger's seed
(simulate/analysis/draws.py: $a \in \{-0.9, -0.5, 0.5, 2\}$, $b \in \{0.5, 2\}$, energy scales $0.5, 1, 2$),
integrated in heyoka's batch mode with a MEGNO tangent vector (simulate/analysis/chaos.py), analysed by NAFF
(simulate/analysis/naff.py) and classified by the rules of simulate/analysis/rules.py, fixed beforehand.

* **S5:EJ-tori** (lines 884-885). "The regular compact level sets of the integrals which have no
  equilibrium points are 2-tori where the flow is quasi-periodic after a time reparametrisation."
  Our reading (``printed.section5.euler_jacobi_torus_dimension``): the reduced flow eq:red-system on
  such a level set has 2 independent frequencies, and (Kolmogorov: a smooth invariant measure and
  an irrational rotation number make the flow on $T^2$ smoothly conjugate to a linear one) every
  orbit of one level set has the same rotation number $\omega_1/\omega_2$. Measured on 50 level sets,
  4 orbits each (1 drawn, 3 moved across the flow on its level set).
* **S5:reconstruction** (line 885): "Determining the nature of the reconstruction of this type of
  dynamics to $P$ is a difficult problem for which little is known." The paper states no number
  (``printed.section5.reconstruction_statement`` is None). For a relative periodic orbit of a
  compact group the reconstructed motion lies on tori of dimension at most 1 + rank (Field,
  Krupa); for a reduced 2-torus it is quasi-periodic on tori of dimension at most 2 + rank $SO(3)$
  = 3 exactly when the reconstruction equation is reducible, i.e. when the reduced torus's
  generators have commuting $SO(3)$-invariant lifts (Fassò, García-Naranjo, Giacobbe, arXiv:1411.7976;
  no row supplies them: ``RECONSTRUCTION_NOTES``). Measured: the count on $P$ (expected 3, the
  generic case of that bound) and, for the same orbits, on the two $SO(3)$-invariant observables
  (expected 2). Orbits whose count exceeds 3 are re-examined to $8T$ by the rule of
  simulate/analysis/reconstruction.py (validated on tori of known dimension).
* **Th:Re-tori:frequencies** (lines 579-580, row Th:Re-tori decided exactly). On $\mathcal V$ for
  $n = 4..7$ (50 drawn points each, the full field eq:motion-general): $\lfloor(n-1)/2\rfloor$
  independent frequencies for $a \ne 0$, none (an equilibrium) at $a = 0$.

Control (all three rows): the $n = 4$ sphere with the generic mass tensor ``CHAOTIC_J[4]`` =
diag(1, 2, 0.5, 0.25), chosen by a MEGNO-only rule (simulate/analysis/control.py), 100 drawn orbits, the same
analysis.
"""

from __future__ import annotations

import numpy as np
from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.proofs import drawn_common as dc
from chaplygin_nd.simulate.analysis import evidence_rows as er
from chaplygin_nd.simulate.analysis import reconstruction as recon
from chaplygin_nd.simulate.analysis.chaos import LADDER_BOUNDED, LADDER_GROWTH, MEGNO_CHAOTIC
from chaplygin_nd.simulate.analysis.control import CHAOTIC_J
from chaplygin_nd.simulate.analysis.drawn_evidence import BATCH, TOL
from chaplygin_nd.simulate.analysis.frequencies import REGULAR
from chaplygin_nd.symbolic.exact.points import ledger_seed
from chaplygin_nd.symbolic.printed import section4 as printed4
from chaplygin_nd.symbolic.printed import section5 as printed5

SECTION4 = "Section 4 — the axisymmetric sphere"
SECTION5 = "Section 5 — n = 4"
ROTATION_AGREE = 1e-6     # relative: the same rotation number on one level set
ZETA_AGREE = 0.98         # of the resolved orbits on V: agree with the exact frequencies of zeta

SETTINGS = (f"heyoka Taylor (batch of {BATCH}, compact mode, tol {TOL:g}) with a MEGNO tangent vector; "
            f"NAFF vectorised over orbits (order-2 Hann window) on complex observables; "
            f"integer-relation search |coefficients| <= 4, relative tolerance max(1e-7, 10 D), "
            f"lines beyond it explained by combinations |c| <= 12 when the false-match probability "
            f"is <= 1 %; regular: D < {REGULAR:g}, unresolved orbits again at 2T and 4T; chaos by "
            f"the MEGNO horizon ladder (T/8..T: growth >= {LADDER_GROWTH:g} over the last doubling "
            f"and <Y> >= {MEGNO_CHAOTIC:g}: chaotic; |growth| <= {LADDER_BOUNDED:g}: regular); the "
            f"proved integrals along every orbit (drift <= 1e-6)")


def rates() -> str:
    """The validation study's false-alarm and miss rates of the chaos rule (bench/bench_evidence.py)."""
    return f"validation of the chaos rule on systems with known answers: {dc.STUDY}"


def _control():
    results = er.control4_row(ledger_seed())["results"]
    return results, dc.describe(results, f"control, generic J = diag{CHAOTIC_J[4]}")


def _verdict(row_id: str, results, rerun, *, measured: str, contradiction: str, method: str, n_values,
             extra_support: bool = True, extra_part: str = "frequencies", notes: str = "",
             data: dict | None = None) -> Verdict:
    control, control_text = _control()
    on_megno, on_freq = dc.separates(results, control)
    ok = dc.supported(results) and extra_support
    # an open row says first which part of the rule fixed beforehand failed
    unmet = dc.unmet(results) + ([] if extra_support else [f"{extra_part}: the row's own condition "
                                                           "(see the contradiction) fails"])
    parts = dc.parts(results)
    parts[extra_part] = parts[extra_part] and extra_support
    return Verdict.numerical(
        ok, measured=(measured + "; " + dc.describe(results, "drawn orbits") + "; "
                      + dc.integrals_text(results) + "; " + dc.ladder_text(results)
                      + f"; of the {len(rerun)} orbits unresolved at T, after the ladder: "
                      + (dc.tally(rerun) if rerun else "none") + "; resonances: "
                      + dc.resonances(results)),
        initial_conditions=len(results),
        tolerance=f"{SETTINGS}; rule: {dc.RULE}",
        contradiction=contradiction + "; " + dc.RULE,
        control=(control_text + f"; separates on the chaos indicator: {on_megno}, on the frequency "
                 f"diffusion: {on_freq}"),
        control_separates=on_megno and on_freq,
        method=method + "; " + rates() + "; " + dc.PLANTED[row_id],
        n_values=n_values, notes=notes, unmet=unmet,
        data={"orbits": dc.record(results), "rerun": dc.record(rerun), "parts": parts,
              "control_orbits": dc.record(control), **(data or {})})


def _same_prediction(printed: int, setting) -> None:
    """The orbits were classified against ``setting.expected``; it must be the paper's number (a
    different reading would need a new classification, not a verdict on the old one)."""
    if printed != setting.expected:
        raise ValueError(f"{setting.name}: the paper's reading predicts {printed} frequencies, the "
                         f"drawn orbits were classified against {setting.expected}")


def _rotation_agreement(out) -> tuple[int, int, float]:
    """(level sets with >= 2 predicted orbits, those whose rotation numbers agree to
    ROTATION_AGREE, the worst relative spread)."""
    res = out["results"]
    tested = agree = 0
    worst = 0.0
    for group in out["groups"]:
        rho = [res[i].frequencies[0] / res[i].frequencies[1] for i in group
               if res[i].cls == "predicted"]
        if len(rho) < 2:
            continue
        tested += 1
        spread = (max(rho) - min(rho)) / abs(np.mean(rho))
        worst = max(worst, float(spread))
        agree += int(spread <= ROTATION_AGREE)
    return tested, agree, worst


@claim("S5:EJ-tori", uses=("eq:red-system", "S5:red-integrals", "S5:red-measure"),
       adds=(SECTION5, "regular compact level sets of (F1, F2, F3, H) in R are 2-tori with "
                       "quasi-periodic flow after a time change (lines 884-885): numerical evidence"))
def s5_ej_tori() -> Verdict:
    expected = int(printed5.euler_jacobi_torus_dimension())  # read even when nothing is measured
    _same_prediction(expected, er.SETTINGS["reduced"])
    if reason := dc.without_heyoka():
        return Verdict.open(reason)
    er.start_shared("control4", ledger_seed())  # the shared control first, unless another row has it
    out = er.reduced_row(ledger_seed())
    tested, agree, worst = _rotation_agreement(out)
    return _verdict(
        "S5:EJ-tori", out["results"], out["rerun"],
        measured=(f"eq:red-system on {len(out['groups'])} drawn level sets x 4 orbits (level-set "
                  f"points Newton did not reach: {out['failed']}); expected {expected} independent "
                  f"frequencies; rotation number w1/w2 the same on {agree} of the {tested} level "
                  f"sets with >= 2 predicted orbits (worst relative spread {worst:.1e})"),
        contradiction=(f"a regular orbit with a third independent frequency, chaos, or rotation "
                       f"numbers differing by more than {ROTATION_AGREE:g} within one level set on "
                       "more than 2 % of the level sets tested"),
        extra_support=tested > 0 and (tested - agree) <= dc.CONTRADICTING_MAX * tested,
        method=f"numerical: eq:red-system (generated expression builders), {SETTINGS}",
        n_values=(4,), data={"rotation_level_sets": [tested, agree, worst]})


@claim("S5:reconstruction", uses=("eq:motion-n4", "S5:SO3-action", "S5:EJ-tori"),
       adds=(SECTION5, "the reconstruction of the reduced dynamics to P (line 885: 'little is "
                       "known'): measured number of independent frequencies on P"))
def s5_reconstruction() -> Verdict:
    assert printed5.reconstruction_statement() is None  # the paper states no number
    bound = int(printed5.euler_jacobi_torus_dimension() + printed5.so3_rank())
    _same_prediction(bound, er.SETTINGS["full4"])
    if reason := dc.without_heyoka():
        return Verdict.open(reason)
    for shared in ("control4", "full4"):  # each shared ensemble now, unless another row has it
        er.start_shared(shared, ledger_seed())
    out = er.full4_row(ledger_seed())
    counted = out["results"]
    examined = recon.reexamine_row(er.SETTINGS["full4"], ledger_seed(), counted)
    res = [recon.reread(r, examined[k]) if k in examined else r for k, r in enumerate(counted)]
    inv = {}
    for r in res:
        if r.invariant_diffusion < REGULAR:
            inv[r.invariant_count] = inv.get(r.invariant_count, 0) + 1
    resolved_inv = sum(inv.values())
    rerun = [res[k] for k in out["rerun_index"]]
    return _verdict(
        "S5:reconstruction", res, rerun,
        measured=(f"eq:motion-general on P, 200 drawn generic orbits; generic case of the bound: "
                  f"exactly {bound} = 2 + rank SO(3) independent frequencies; the two "
                  f"SO(3)-invariant observables alone (resolved on {resolved_inv} orbits): "
                  + ", ".join(f"{c} frequencies on {k}" for c, k in sorted(inv.items()))
                  + "; " + _reexamined_text(examined, len(res))),
        contradiction=(f"a regular generic orbit with more than {bound} independent frequencies "
                       "(beyond the bound of the reconstruction) or chaos; an orbit the count calls "
                       "excess contradicts only if its re-examination finds a fourth frequency"),
        method=(f"numerical: eq:motion-general, generated L_gamma^-1 (expression builders), {SETTINGS}; "
                f"orbits the count calls excess re-examined ({RECONSTRUCTION_RULE}; {recon.STUDY})"),
        n_values=(4,), notes=RECONSTRUCTION_NOTES,
        data={"invariant_counts": inv,
              "reexamined": {str(k): {"class": e.cls, "reason": e.reason, "track": e.track,
                                      "resonance": e.resonance,
                                      "diffusion": [lk.diffusion for lk in e.looks],
                                      "lattice": e.looks[-1].fit.get("basis")}
                             for k, e in examined.items()}})


RECONSTRUCTION_RULE = (
    "rule of simulate/analysis/reconstruction.py: one straight run from t = 0 to 8T at the row's "
    "tolerance and sampling, NAFF at T, 2T, 4T, 8T; unresolved if D(8T) >= 1e-5; rank 3 if a basis "
    "of 3 of the 8 strongest lines at 8T explains every strong line credibly (|c| <= 4, 12, 24 at "
    "the line's measured precision, 3 x its move from 4T to 8T, or |c| <= 4 at the row's "
    "tolerance; chance of a false match <= 1 %); fourth frequency if a line stays unexplained, is "
    "precise enough to be tested and stays put (<= 0.1 Fourier bin, amplitude within 2x from 4T "
    "to 8T); transient otherwise; only a fourth frequency contradicts")

RECONSTRUCTION_NOTES = (
    "the paper leaves the reconstruction open (line 885, citing Zung and Fasso-Garcia-Naranjo-"
    "Giacobbe) and this row reports a measurement, not a proof. What a proof would need: (1) the "
    "reduced flow quasi-periodic on the regular level sets (Euler-Jacobi on P/SO(3): its invariant "
    "measure is S5:red-measure and its 4 integrals S5:red-integrals, both decided exactly; compact "
    "energy levels from L_gamma > 0, eq:M-O; that the regular level sets are compact and free of "
    "equilibria is argued in the paper, measured in S5:EJ-tori); (2) the group compact and acting "
    "properly: SO(3), S5:SO3-action, decided exactly; (3) the step no row discharges: for a "
    "reduced torus of dimension 2 the reconstructed flow need not be quasi-periodic even for a "
    "compact group (Fasso, Garcia-Naranjo, Giacobbe, Nonlinearity 28 (2015), arXiv:1411.7976) - it "
    "is, on tori of dimension at most 2 + rank SO(3) = 3, iff the reconstruction equation is "
    "reducible, equivalently iff the generators of the reduced torus have commuting SO(3)-invariant "
    "lifts; Zung (Reduction and integrability, arXiv:math/0201087) proves the lift for Hamiltonian "
    "systems with a Hamiltonian action of a compact group, and only the converse direction "
    "(integrable implies reduced integrable) without a Hamiltonian structure. A Hamiltonisation "
    "on P (S7:poisson-n4, open: none in the searched boxes) or the commuting invariant fields "
    "themselves (S7:symmetry-fields, open) would supply (3)")


def _reexamined_text(examined: dict, total: int) -> str:
    """One phrase: what the re-examination made of the orbits the count called excess."""
    if not examined:
        return "no orbit with a line the count could not explain"
    parts = [f"orbit {k}: {e.cls} ({e.reason})" for k, e in sorted(examined.items())]
    doubtful = sum(e.cls != "rank 3" for e in examined.values())
    return (f"the count called {len(examined)} orbits excess; re-examined to 8T: " + "; ".join(parts)
            + f"; counting every re-examined orbit not read rank 3 as contradicting (the rule's "
            f"misses are unresolved or transient readings): {doubtful} of {total}")


@claim("Th:Re-tori:frequencies", uses=("Th:Re", "Th:Re-tori"),
       adds=(SECTION4, "numerical confirmation of the torus dimension on V for n = 4..7: "
                       "floor((n-1)/2) frequencies for a != 0, none at a = 0"))
def th_re_tori_frequencies() -> Verdict:
    for n in er.VERTICAL_T:  # the printed predictions are read even when nothing is measured
        _same_prediction(int(printed4.vertical_torus_dimension(n)), er.vertical_setting(n))
    if reason := dc.without_heyoka():
        return Verdict.open(reason)
    er.start_shared("control4", ledger_seed())  # the shared control first, unless another row has it
    out = er.vertical_row(ledger_seed())
    results, rerun, per_n, zeta, slow = [], [], [], [], 0
    for n, o in out.items():
        _same_prediction(int(printed4.vertical_torus_dimension(n)), er.vertical_setting(n))
        results += o["results"]
        rerun += o["rerun"]
        zeta += o["zeta"]
        # turns of the slowest exact rate in half of the longest horizon (4T)
        half = er.LADDER_FACTORS[-1] * er.VERTICAL_T[n] / 2
        slow += sum(1 for r, z in zip(o["results"], o["zeta"]) if r.cls == "unresolved"
                    and z["rates"] and min(z["rates"]) * half / (2 * np.pi) < 10)
        per_n.append(f"n={n} (expected {int(printed4.vertical_torus_dimension(n))}, 0 at a = 0): "
                     f"{dc.tally(o['results'])}")
    resolved = [(r, z) for r, z in zip(results, zeta) if r.cls != "unresolved"]
    agree = sum(z["agrees"] for _, z in resolved)
    errors = [z["error"] for _, z in resolved]
    worst = max(errors, default=0.0)
    zeta_ok = bool(resolved) and agree >= ZETA_AGREE * len(resolved)
    unresolved = sum(r.cls == "unresolved" for r in results)
    return _verdict(
        "Th:Re-tori:frequencies", results, rerun,
        measured=("; ".join(per_n) + f"; against the exact answer (Th:Re: M, gamma move by exp(t zeta), "
                  f"the lines are integer combinations of the rates of the derived zeta): "
                  f"{agree} of the {len(resolved)} resolved orbits agree (count = number of rates, "
                  f"every measured frequency within {er.ZETA_MATCH:g} resolutions 2 pi/T of a "
                  f"combination |c| <= 2 of the rates); error median "
                  f"{float(np.median(errors)) if errors else float('nan'):.1e}, worst {worst:.1e} "
                  f"resolutions; of the {unresolved} orbits unresolved after 4T, {slow} have a rate "
                  "making fewer than 10 turns in half of 4T (the lines cannot be resolved there)"),
        contradiction=("a regular orbit with more than floor((n-1)/2) frequencies (any line at a = 0), "
                       f"chaos, or fewer than {100 * ZETA_AGREE:g} % of the resolved orbits agreeing "
                       "with the exact frequencies of zeta"),
        extra_support=zeta_ok, extra_part="frequencies",
        method=(f"numerical: eq:motion-general for n = 4..7 from drawn points of V, {SETTINGS}; the "
                "chaos indicator's tangent vector starts in the tangent space of V: the statement is "
                "about the flow on V, and in the whole space the tangent of even n grows like t^2 "
                "(<Y> -> 4, still rising at T: the old single threshold left 45 of 64 such study "
                "orbits undecided, the ladder 3, with the tangent in TV 0); the frequencies compared "
                "with the eigenvalues of the derived zeta"),
        n_values=tuple(out), notes="a = 0 gives an equilibrium (no frequency), as Th:Re-tori's "
                                   "correction states",
        data={"zeta": [{"error": z["error"], "agrees": z["agrees"], "rank": z["rank"]} for z in zeta]})
