"""Tools for working on layoutdsl itself (not used by the pipeline)."""
