"""Hostile and careless use of every command and of the API (issues 12 and 19).

The tables of cases, each run by one parametrized test:

* ``cli_<command>.py``: one module per command, each declaring its command with
  :func:`robustness.harness.command` (title, and the first function of its work, which the
  tests replace by a tripwire) and its cases with :func:`robustness.harness.case`. Bad
  arguments, configuration files, input files, manifests, baselines and output folders:
  each must end with exit status 2 and ONE line on stderr (``irnuc COMMAND: error: ...``)
  naming the flag, file or dotted field, with no traceback, before the command's work
  starts, and with the output name exactly as it was (nothing created, nothing replaced,
  no temporary folder left). Every ``cli_*.py`` module of this folder is collected
  (:func:`robustness.harness.load_tables`): a new command adds its own module.
* ``api_cases.py``: the model and golden-model API raise ``ValueError`` naming the
  argument for bad shapes, dtypes, empty or non-finite input; any integer byte order is
  accepted and gives the native result.
* ``faults.py``: SIGKILL at random points, concurrent runs on one ``--out``, children that
  die with their parent (the tests are in ``test_faults.py``).
* ``memory.py``: the memory estimates checked before the work stay above measured peaks.
* ``outcomes.py``: hostile inputs whose right outcome is not only an error line before the
  work (write and stdout errors, runs that check nothing, results that were silently
  wrong); ``test_outcomes.py`` checks each row.

``docs/robustness.md`` is generated from these tables (``.venv/bin/python
tests/robustness/doc.py`` rewrites it) and ``test_doc.py`` keeps it in step.

To add cases: for an existing command, append ``case(...)`` lines to its ``cli_<command>.py``
(a file the case needs of its own is made by ``setup=``; files several cases share go into
``world.py``, the ``world`` fixture of ``conftest.py``). For a new command, add
``cli_<command>.py`` holding ``X = command("<command>", (("irnuc.module", "work_fn"),))``
and its cases; it is collected and documented without other edits. Then rewrite the doc.
Modules here import each other as ``robustness.<module>`` (the folder is a package; pytest's
importlib mode imports it as such, and ``doc.py`` puts ``tests/`` on the path when run).
"""
