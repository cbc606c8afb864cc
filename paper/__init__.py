"""The paper (``chaplygin-sphere-nd.tex``) and its claims (``CLAIMS.md``), shipped as package
data: :mod:`chaplygin_nd.ledger.catalog` reads them with :mod:`importlib.resources`. No code."""
