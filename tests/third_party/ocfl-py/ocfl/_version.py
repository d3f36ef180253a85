"""Version number for this Python implementation of OCFL."""
__version__ = "2.1.0"
