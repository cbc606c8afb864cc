"""Power of the evidence rows on a planted defect, the cheapest case: the sign of one
term of the full field flipped (bench/planted.py ``sign``) in a temporary copy of the package,
never in the tree. The defect must first break the proved integrals (else it is no defect); then
the rows' rule (simulate/analysis/rules.py) on those orbits must not support the statement, and must
say that the integrals caught it. The full table (every row, both defects, the reduced field) is
in ``chaplygin bench evidence``."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from dataclasses import replace

import pytest
from chaplygin_nd.bench import planted
from chaplygin_nd.proofs import drawn_common as dc
from chaplygin_nd.simulate.analysis import draws
from chaplygin_nd.simulate.analysis import evidence_rows as er
from chaplygin_nd.simulate.analysis.drawn_evidence import OrbitResult, measure
from chaplygin_nd.simulate.analysis.kept import KEPT

pytest.importorskip("heyoka")

_RUN = """
import json, sys
sys.path.insert(0, {pkg!r})
from dataclasses import replace
from chaplygin_nd.simulate.analysis import draws, evidence_rows as er
from chaplygin_nd.simulate.analysis.drawn_evidence import measure
import chaplygin_nd.generated.expression_builders as eb
assert eb.__file__.startswith({pkg!r})
s = replace(er.SETTINGS["full4"], name="planted-test", T=256.0)
ens = draws.draw("planted-test", "generic", 4, 8, 3)
print(json.dumps([r.to_dict() for r in measure(s, ens, er._full_state(ens), 3, use_cache=False)]))
"""


def _orbits():
    s = replace(er.SETTINGS["full4"], name="planted-test", T=256.0)
    ens = draws.draw("planted-test", "generic", 4, 8, 3)
    return s, ens, er._full_state(ens)


def test_a_flipped_sign_breaks_the_integrals_and_the_rule_says_so(tmp_path):
    name, old, new, _rows = next(d for d in planted.DEFECTS if d[0] == "sign")
    pkg = planted.copy_package(tmp_path / "site")
    planted.plant(pkg, old, new)
    env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
    env["CHAPLYGIN_ND_CACHE"] = str(tmp_path / "cache")
    r = subprocess.run([sys.executable, "-I", "-B", "-c", _RUN.format(pkg=str(pkg))], env=env,
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    wrong = [OrbitResult(**d) for d in json.loads(r.stdout.strip().splitlines()[-1])]
    right = measure(*_orbits(), 3, use_cache=False)          # the tree's field, the same orbits
    assert all(o.drift <= KEPT for o in right), [o.drift for o in right]
    assert all(o.drift > 100 * KEPT for o in wrong), [o.drift for o in wrong]   # a real defect
    assert dc.parts(right)["integrals"] and not dc.parts(wrong)["integrals"]
    assert not dc.supported(wrong)
    assert dc.unmet(wrong)[0].startswith("integrals: 0 of 8 orbits keep")
