"""The built-in scenes (``*.toml``; the format in ``README.md``), shipped as package data:
:mod:`chaplygin_nd.simulate.scene.spec` reads them with :mod:`importlib.resources`. No code."""
