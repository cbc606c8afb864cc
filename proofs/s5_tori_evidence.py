r"""Section 5's qualitative dynamics as numerical evidence (issue 11): S5:EJ-tori,
S5:reconstruction and Th:Re-tori:frequencies.

No identity can decide these statements; a measurement can support them, and a control shows
that the measurement could have come out otherwise. Verdict ``evidence`` (never ``holds``), or
``open`` with the numbers when the measurement does not support the statement or the control
does not separate.

* **S5:EJ-tori** (lines 884-885). "The regular compact level sets of the integrals which have no
  equilibrium points are 2-tori where the flow is quasi-periodic after a time reparametrisation."
  Our reading (``printed.section5.euler_jacobi_torus_dimension``): the reduced flow eq:red-system on
  such a level set has 2 independent frequencies. By Kolmogorov's theorem a flow on $T^2$ with a
  smooth invariant measure and an irrational rotation number is smoothly conjugate to a linear
  flow, so in physical time too the spectrum lies on a rank-2 lattice, and every orbit of the same
  torus has the same frequencies (only the phases of the lines differ). Measured: the number of
  independent frequencies of each orbit, the rotation number $\omega_1/\omega_2$ on 3 orbits of
  one level set (1 from the seeded point, 2 moved across the flow on its level set) and on a second
  level set, and that the Poincaré section $\{G = 0, \dot G < 0\}$ of each orbit is a closed curve.
* **S5:reconstruction** (line 885): "Determining the nature of the reconstruction of this type of
  dynamics to $P$ is a difficult problem for which little is known." The paper states nothing to
  check (``printed.section5.reconstruction_statement`` is None). For a compact symmetry group the
  reconstruction of a quasi-periodic reduced flow is expected to be quasi-periodic on tori of
  dimension at most (reduced torus dimension) + rank $SO(3)$ = 2 + 1 = 3 (Field, Krupa), with
  equality for generic orbits. Measured: the number of independent frequencies of the full flow
  on $P$ over generic initial conditions (the row supports "exactly 3"; any other count is
  reported as open with the numbers), and that the reduced frequencies of the same orbit lie in
  its lattice.
* **Th:Re-tori:frequencies** (lines 579-580, row Th:Re-tori decided exactly). Numerically, on
  $\mathcal{V}$ for $n = 4..7$: $\lfloor(n-1)/2\rfloor$ independent frequencies for $a \neq 0$ and none
  (an equilibrium) at $a = 0$ — integrating the full field eq:motion-general, not the closed form; the
  measured frequencies are compared with the rotation rates of $\zeta$ (Th:Re).

Control (all three rows): the $n = 4$ sphere with a generic mass tensor (simulate/control.py),
same analysis and orbit length; it must have a frequency diffusion at least 100 times the largest
of the rows' orbits (threshold fixed in simulate/frequencies.py before looking).
"""

from __future__ import annotations

import math

from chaplygin_nd.ledger.registry import Verdict, claim
from chaplygin_nd.simulate import frequencies as fq
from chaplygin_nd.simulate import naff
from chaplygin_nd.simulate.evidence import orbits
from chaplygin_nd.simulate.poincare import section_curve_scatter
from chaplygin_nd.symbolic.printed import section4 as printed4
from chaplygin_nd.symbolic.printed import section5 as printed5

SECTION4 = "Section 4 — the axisymmetric sphere"
SECTION5 = "Section 5 — n = 4"
ROTATION_AGREE = 1e-6     # relative: the same rotation number on one level set
ROTATION_DIFFER = 1e-3    # relative: a different level set has a measurably different one
CURVE = 0.05              # section scatter below which the section is a curve (a cloud: ~0.3-1)


def _fmt(xs, digits=8) -> str:
    return "[" + ", ".join(f"{x:.{digits}g}" for x in xs) + "]"


def _control() -> tuple[list[float], str]:
    specs = fq.spectra(fq.control_experiment())
    ds = [s.diffusion for s in specs]
    return ds, (f"n = 4 sphere with generic J = diag{fq.CONTROL_J}, b = {fq.B}, the same "
                f"{len(ds)} initial conditions and T = {fq.T_END:g}: diffusion {_fmt(ds, 3)}")


def _settings(exp) -> str:
    return (f"DOP853 rtol = atol = {exp.rtol:g}, T = {exp.samples * exp.dt:g}, dt = {exp.dt:g}; "
            f"NAFF (PyNAFF, Hann window) on complex observables; integer-relation search with "
            f"|coefficients| <= 4, relative tolerance max(1e-7, 10 D)")


@claim("S5:EJ-tori", uses=("eq:red-system", "S5:red-integrals", "S5:red-measure"),
       adds=(SECTION5, "regular compact level sets of (F1, F2, F3, H) in R are 2-tori with "
                       "quasi-periodic flow after a time change (lines 884-885): numerical evidence"))
def s5_ej_tori() -> Verdict:
    exp = fq.reduced_experiment()
    specs = fq.spectra(exp)
    expected = int(printed5.euler_jacobi_torus_dimension())
    same = 1 + len(fq.LEVEL_SHIFTS)
    counts = [s.count for s in specs]
    ds = [s.diffusion for s in specs]
    rho = [fq.rotation_number(s) for s in specs]
    orb = orbits(exp)
    scatter = [section_curve_scatter(orb.y[:, m], exp) for m in range(orb.y.shape[1])]
    ref = rho[0]
    agree = max(abs(r - ref) / ref for r in rho[:same]) if not math.isnan(ref) else math.inf
    differ = min(abs(r - ref) / ref for r in rho[same:]) if not math.isnan(ref) else 0.0
    regular = all(d < fq.REGULAR for d in ds)
    supported = (regular and all(c == expected for c in counts) and agree <= ROTATION_AGREE
                 and differ >= ROTATION_DIFFER and all(s <= CURVE for s in scatter))
    control_d, control = _control()
    cexp = fq.control_experiment()
    corb = orbits(cexp)
    control_scatter = [section_curve_scatter(corb.y[:, m], cexp) for m in range(corb.y.shape[1])]
    control += f"; its Poincare section scatter {_fmt(control_scatter, 2)}"
    return Verdict.numerical(
        supported,
        measured=(f"independent frequencies per orbit {counts} (expected {expected}); "
                  f"frequencies {' '.join(_fmt(s.frequencies) for s in specs)}; diffusion {_fmt(ds, 3)}; "
                  f"rotation numbers {_fmt(rho, 10)}: the {same} orbits of level set L1 agree to "
                  f"{agree:.1e}, L2 differs by {differ:.1e}; Poincare section scatter "
                  f"{_fmt(scatter, 2)}"),
        initial_conditions=len(specs),
        tolerance=(f"regular: D < {fq.REGULAR:g}; same rotation number: relative {ROTATION_AGREE:g}; "
                   f"a closed curve: scatter <= {CURVE:g}; {_settings(exp)}"),
        contradiction=("a regular orbit with a third independent frequency, a rotation number that "
                       "differs between orbits of one level set, or a section that is a cloud"),
        control=control,
        control_separates=fq.separates(ds, control_d) and min(control_scatter) > CURVE,
        method=f"numerical: eq:red-system (generated kernel), {_settings(exp)}", n_values=(4,),
        data={"counts": counts, "diffusion": ds, "rotation_numbers": rho,
              "section_scatter": scatter, "control_diffusion": control_d,
              "control_section_scatter": control_scatter})


@claim("S5:reconstruction", uses=("eq:motion-n4", "S5:SO3-action", "S5:EJ-tori"),
       adds=(SECTION5, "the reconstruction of the reduced dynamics to P (line 885: 'little is "
                       "known'): measured number of independent frequencies on P"))
def s5_reconstruction() -> Verdict:
    assert printed5.reconstruction_statement() is None  # the paper states no number
    bound = int(printed5.euler_jacobi_torus_dimension() + printed5.so3_rank())
    exp = fq.full_experiment()
    specs = fq.spectra(exp)
    reduced = fq.spectra(fq.reduced_experiment())
    counts = [s.count for s in specs]
    ds = [s.diffusion for s in specs]
    # The reduced orbit of full member m: member 1 -> the L2 orbit (last), member 3 -> L1 (first).
    partner = {1: reduced[-1], 3: reduced[0]}
    inside = []
    for m, s in zip(fq.GENERIC_MEMBERS, specs):
        r = partner.get(m)
        if r is None:
            continue
        tol = s.tolerance * max(s.frequencies, default=1.0)
        inside.append(all(naff.independent_frequencies(s.frequencies + [f], tol)
                          == naff.independent_frequencies(s.frequencies, tol)
                          for f in r.frequencies))
    regular = all(d < fq.REGULAR for d in ds)
    supported = regular and all(c == bound for c in counts) and all(inside)
    control_d, control = _control()
    return Verdict.numerical(
        supported,
        measured=(f"independent frequencies of the full flow on P per orbit {counts} (generic "
                  f"case of the bound: exactly {bound} = 2 + rank SO(3)); frequencies "
                  f"{' '.join(_fmt(s.frequencies) for s in specs)}; diffusion {_fmt(ds, 3)}; the reduced "
                  f"frequencies of the same orbits lie in these lattices: {inside}"),
        initial_conditions=len(specs),
        tolerance=f"regular: D < {fq.REGULAR:g}; {_settings(exp)}",
        contradiction=(f"a regular generic orbit with other than {bound} independent frequencies "
                       "(more would break the bound; fewer, a degenerate reconstruction), a "
                       "reduced frequency outside the lattice, or irregular (diffusing) orbits"),
        control=control, control_separates=fq.separates(ds, control_d),
        method=f"numerical: eq:motion-general, generated L_gamma^-1, {_settings(exp)}",
        n_values=(4,),
        notes=("the paper leaves the reconstruction open; this row reports what was measured: "
               "the flow on P is quasi-periodic on tori of dimension " + "/".join(map(str, counts))),
        data={"counts": counts, "diffusion": ds, "control_diffusion": control_d})


@claim("Th:Re-tori:frequencies", uses=("Th:Re", "Th:Re-tori"),
       adds=(SECTION4, "numerical confirmation of the torus dimension on V for n = 4..7: "
                       "floor((n-1)/2) frequencies for a != 0, none at a = 0"))
def th_re_tori_frequencies() -> Verdict:
    rows, ok, ds, worst_rate = [], True, [], 0.0
    for n in fq.VERTICAL_NS:
        for a in fq.VERTICAL_A:
            exp = fq.vertical_experiment(n, a)
            s = fq.spectra(exp)[0]
            expected = int(printed4.vertical_torus_dimension(n)) if a != 0 else 0
            if a != 0:
                ds.append(s.diffusion)
                rates = fq.zeta_rates(exp)
                tol = s.tolerance * max(s.frequencies + rates)
                both = naff.independent_frequencies(s.frequencies + rates, tol)
                same = len(both) == s.count == len(rates)
                worst_rate = max(worst_rate, 0.0 if same else math.inf)
                ok = ok and same and s.diffusion < fq.REGULAR
            ok = ok and s.count == expected
            rows.append(f"n={n} a={a:g}: {s.count} (expected {expected}) {_fmt(s.frequencies)}")
    control_d, control = _control()
    exp = fq.vertical_experiment(4, fq.A)
    return Verdict.numerical(
        ok,
        measured=("; ".join(rows) + f"; diffusion (a != 0) {_fmt(ds, 3)}; the measured frequencies span the same "
                  f"lattice as the rotation rates of zeta (Th:Re): {worst_rate == 0.0}"),
        initial_conditions=2 * len(fq.VERTICAL_NS),
        tolerance=(f"regular: D < {fq.REGULAR:g}; same lattice as the rates of zeta: the "
                   "integer-relation tolerance; constant signal: "
                   f"variation <= 1e-6 of its size; {_settings(exp)}"),
        contradiction=("a count other than floor((n-1)/2) for a != 0, any line at a = 0, or "
                       "frequencies that are not the rotation rates of zeta"),
        control=control, control_separates=fq.separates(ds, control_d),
        method=f"numerical: eq:motion-general for n = 4..7 from seeded points of V, {_settings(exp)}",
        n_values=fq.VERTICAL_NS,
        notes="a = 0 gives an equilibrium (no frequency), as Th:Re-tori's correction states",
        data={"diffusion": ds, "control_diffusion": control_d})
