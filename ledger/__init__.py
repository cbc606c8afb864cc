"""The ledger's machinery, apart from the claims it runs (:mod:`chaplygin_nd.proofs`).

* :mod:`~chaplygin_nd.ledger.registry` — verdicts, parts and the ``@claim`` registry a claim
  script uses (re-exported here: ``from chaplygin_nd.ledger import Verdict, claim``);
* :mod:`~chaplygin_nd.ledger.catalog` — the rows (``CLAIMS.md`` and the rows this project adds)
  and the discovery of the claim scripts;
* :mod:`~chaplygin_nd.ledger.runner` — decides rows, in worker processes;
* :mod:`~chaplygin_nd.ledger.report`, :mod:`~chaplygin_nd.ledger.graph` — VERIFICATION.md,
  verification.json and the claim graph;
* :mod:`~chaplygin_nd.ledger.reach`, :mod:`~chaplygin_nd.ledger.remap` — which printed formulas
  and derivations each row reaches;
* :mod:`~chaplygin_nd.ledger.mutation` — mutation testing of them (``chaplygin mutate``,
  ``chaplygin mutate-derivations``), a subpackage of its own;
* ``python -m chaplygin_nd.ledger`` (``chaplygin verify`` / ``chaplygin prove``) — the command.
"""

from chaplygin_nd.ledger.registry import (
    ERRATA_KINDS,
    KINDS,
    VERDICTS,
    ClaimSpec,
    Part,
    Verdict,
    claim,
    registry,
)

__all__ = ["Verdict", "Part", "claim", "registry", "ClaimSpec", "VERDICTS", "KINDS", "ERRATA_KINDS"]
