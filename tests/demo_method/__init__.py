"""A demonstration correction method kept in the tests (issue 38): ``offset_only``, added by
the steps of docs/architecture.md ("Add a method") without touching a production file."""
