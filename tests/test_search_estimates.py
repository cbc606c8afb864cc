"""The cost estimates the symmetry-field and Poisson searches print before a box: the model has
one term per stage the search times, grows with the box, and a box above the limit is refused in
one line that names the override. (Structure only: tests assert correctness, never speed.)"""

from __future__ import annotations

import sympy as sp
from chaplygin_nd.symbolic.search import fields_cost as fc
from chaplygin_nd.symbolic.search import symmetry_fields as sf
from chaplygin_nd.symbolic.search.fields_command import main as fields_main
from cli_helpers import exit_code, one_error_line


def test_the_field_estimate_has_one_term_per_stage_the_search_times():
    half = sp.Rational(1, 2)
    r = sf.search_fields(3, 0, -half, half, sp.Rational(1, 3), sp.Rational(2, 5), seed=2)
    assert tuple(r.stages) == fc.STAGES
    assert all(v >= 0 for v in r.stages.values())
    assert set(fc.field_cost(3, 0).stages) == set(fc.STAGES)


def test_the_field_estimate_grows_with_n_and_d_stage_by_stage():
    boxes = [(n, d) for n in range(3, 9) for d in range(4)]
    for n, d in boxes:
        e = fc.field_cost(n, d)
        assert e.columns == fc.FIELDS * (d + 1) - d and e.coordinates == n * (n - 1) // 2 + n
        for bigger in (fc.field_cost(n + 1, d), fc.field_cost(n, d + 1)):
            assert all(bigger.stages[k] >= e.stages[k] for k in fc.STAGES)
            assert bigger.sure > e.sure and bigger.candidate >= e.candidate
        assert e.cpu(2) > e.cpu(1) > e.cpu(0) == e.sure
    f, load = fc.wall_factor()
    assert f >= 1 and load >= 0


def test_an_oversized_field_box_is_refused_in_one_line_naming_the_override(capsys):
    assert exit_code(fields_main, ["40", "6"]) == 2
    line = one_error_line(capsys)
    assert "--max-hours" in line and "nothing was run" in line
    assert exit_code(fields_main, ["3", "0", "--max-hours", "1e-9"]) == 2
    assert "--max-hours" in one_error_line(capsys)


def test_the_poisson_estimate_has_one_term_per_stage_the_search_times_and_grows():
    from chaplygin_nd.symbolic.search import bivector_ansatz as ba
    from chaplygin_nd.symbolic.search import poisson as ps
    from chaplygin_nd.symbolic.search import poisson_cost as pc
    assert pc.BLOCKS == len(ba.MM_NAMES) + len(ba.MG_NAMES)
    r = ps.search_box(3, 2, 1, sp.Rational(1, 3), sp.Rational(2, 5), seed=2)
    assert r.outcome == "solutions" and set(r.stages) <= set(pc.STAGES)
    assert {"conditions", "kernel", "jacobi equations", "groebner"} <= set(r.stages)
    assert set(pc.poisson_cost(3, 0).stages) == set(pc.STAGES)
    for n in range(3, 9):
        for d in range(7):
            e = pc.poisson_cost(n, d)
            for bigger in (pc.poisson_cost(n + 1, d), pc.poisson_cost(n, d + 1)):
                assert all(bigger.stages[k] >= e.stages[k] for k in pc.STAGES)
                assert bigger.sure > e.sure and bigger.jacobi > e.jacobi
            assert e.cpu() > e.sure


def test_an_oversized_poisson_box_is_refused_in_one_line_naming_the_override(capsys):
    from chaplygin_nd.symbolic.search.poisson_command import main as poisson_main
    assert exit_code(poisson_main, ["40", "8"]) == 2
    line = one_error_line(capsys)
    assert "--max-hours" in line and "nothing was run" in line
    # every box of n = 9 up to d = 12 is below the limit, the request is not: refused as a whole
    from chaplygin_nd.symbolic.search import poisson_cost as pc
    assert all(5 * pc.poisson_cost(9, d).cpu() < 24 * 3600 for d in range(13))
    assert exit_code(poisson_main, ["9", "12"]) == 2
    line = one_error_line(capsys)
    assert "in all" in line and "nothing was run" in line
