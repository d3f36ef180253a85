# Surrogate's placeholder for the bagit module, which ocfl-py imports at start (ocfl/bagger.py)
# but its validator never uses, and which Debian 12 does not package. Any use fails loudly.
def __getattr__(name):
    raise ImportError("bagit is not installed; ocfl-py's validator does not need it (tests/third_party/ocfl-py/SOURCE.md)")
