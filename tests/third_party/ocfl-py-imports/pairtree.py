# Surrogate's placeholder for the pairtree module, which ocfl-py imports at start (storage
# root layouts) but its object validator never uses, and which Debian 12 does not package.
def id_encode(identifier):
    raise ImportError("pairtree is not installed; ocfl-py's object validator does not need it")


def id_decode(identifier):
    raise ImportError("pairtree is not installed; ocfl-py's object validator does not need it")
