"""The ``rollspring`` commands, one module each: every module defines its command function and
``register(app)``, which adds it to an app (:mod:`rollspring.cli.app` registers them all).

A command module imports what the commands declare alike from :mod:`rollspring.cli.options`
(the SYSTEM argument, ``--json``, ``--yes``, ``--out``, ``--format``), what they do alike from
:mod:`rollspring.cli.common` (and the terminal helpers :mod:`rollspring.cli.text`,
:mod:`rollspring.cli.tables`), never :mod:`rollspring.cli.app`; what a command computes with
is imported when it runs.
"""
