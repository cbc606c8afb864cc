"""``chaplygin first-integrals`` says what a box will cost before it runs and refuses what cannot
fit (symbolic/search/cost.py): one line, exit status 2, the figure and the override."""

from __future__ import annotations

from chaplygin_nd.symbolic.search import candidate_basis, cost, sampled_field
from chaplygin_nd.symbolic.search.command import main
from chaplygin_nd.symbolic.search.strategies import make_search


def test_the_weight_zero_count_is_the_basis_size():
    """The count over torus weights (nothing built) equals the size of the basis it stands for."""
    for n, d, dg in ((3, 2, 4), (4, 3, 5), (5, 4, 4), (6, 2, 4)):
        planes = (n - 1) // 2
        assert cost.weight_zero_count(n, planes, d, dg) == candidate_basis.basis(n, d, dg, planes).size


def test_the_invariant_estimate_counts_the_unknowns_exactly():
    search = make_search(sampled_field.axisymmetric(5, "-1/3", "3/2"), "invariant")
    est = cost.estimate(search, (4, 4, 1))
    assert est.exact and est.unknowns == sum(search.unknown_counts((4, 4, 1)))
    assert est.largest == max(search.unknown_counts((4, 4, 1)))


def test_n_100_is_refused_before_anything_runs(capsys):
    assert main(["100", "2", "--a", "-1/3", "--b", "3/2"]) == 2
    out, err = capsys.readouterr()
    assert out.count("box (M-degree") == 1 and "2^100 characters" in err
    assert "boxes M-degree 2..2: larger still, not estimated" in out
    assert len(err.strip().splitlines()) == 1 and "--max-hours" in err


def test_a_box_above_the_memory_allowed_is_refused_with_its_figure(capsys):
    argv = ["5", "6", "--from", "6", "--d-gamma", "6", "--k", "2", "--a", "-1/3", "--b", "3/2",
            "--space", "weight-zero", "--max-memory", "0.5"]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert "28396 unknowns" in out and "found" not in out      # the exact count; nothing ran
    assert len(err.strip().splitlines()) == 1 and "GB" in err and "--max-memory" in err


def test_the_invariant_space_where_it_is_not_derived_is_one_error(capsys):
    assert main(["9", "2", "--a", "-1/3", "--b", "3/2", "--space", "invariant"]) == 2
    assert "no invariant generators" in capsys.readouterr().err


def test_the_run_names_its_class_and_says_what_is_left(capsys):
    assert main(["5", "4", "--from", "3", "--a", "-1/3", "--b", "3/2"]) == 0
    out = capsys.readouterr().out
    assert "SO(4)-invariant" in out and "a = -1/3, b = 3/2" in out
    assert "s left" in out and out.count("settled") == 2


def test_primes_mapped_over_processes_print_the_same_table(capsys):
    argv = ["5", "4", "--from", "4", "--a", "-1/3", "--b", "3/2"]
    assert main(argv) == 0
    one = [line for line in capsys.readouterr().out.splitlines() if line.startswith("n=5 d=4")]
    assert main(argv + ["--primes", "2", "--workers", "2"]) == 0
    two = [line for line in capsys.readouterr().out.splitlines() if line.startswith("n=5 d=4")]
    assert "2 primes" not in one[0] and "(primes 2)" in two[0]
    assert one[0].split(", found ")[1].split(",")[0] == two[0].split(", found ")[1].split(",")[0]


def test_a_refusal_names_the_first_box_past_the_limit_and_estimates_no_later_box(capsys, monkeypatch):
    estimated = []
    real = cost.estimate

    def counting(search, box):
        estimated.append(box[0])
        return real(search, box)

    monkeypatch.setattr(cost, "estimate", counting)
    assert main(["9", "30", "--a", "1/3", "--b", "2/5"]) == 2
    captured = capsys.readouterr()
    error = [line for line in captured.err.splitlines() if line.startswith("error:")]
    assert len(error) == 1 and "box (M-degree 4," in error[0] and "--max-hours" in error[0], captured.err
    assert estimated == [1, 2, 3, 4]
    assert "boxes M-degree 5..30: larger still, not estimated" in captured.out
