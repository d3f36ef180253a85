# Surrogate's placeholder for the s3fs module, which ocfl-py imports at start (ocfl/fsw.py) for
# s3:// paths only, and which Debian 12 does not package. Local paths never reach it.
class S3FileSystem:
    def __init__(self, *args, **kwargs):
        raise ImportError("s3fs is not installed; only local OCFL objects can be validated here")
