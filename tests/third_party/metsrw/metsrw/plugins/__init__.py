"""Plugins for metsrw."""
