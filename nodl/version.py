"""The toolkit's version, in a module of its own: what reports and logs name (SARIF's
tool, the analysis log, ``nodl --version``) without importing the package's API."""

__version__ = '0.1.0'
