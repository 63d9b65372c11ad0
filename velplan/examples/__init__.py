"""Bundled example mechanisms (TOML files), loadable by name with `velplan.load`."""
