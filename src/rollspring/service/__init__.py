"""The orchestration layer: what the interfaces (``cli``, ``web``) ask for, computed in order.

analysis -> simulation -> derivation -> report: each interface calls these functions instead
of combining the lower layers itself, and ``outputs`` only renders what they computed.
``systems`` turns what an interface received into a validated system; ``runs`` makes the
analysis and simulation payloads (the CLI's ``--json`` objects, the web API's answers);
``documents`` the derivation, the paper check, worksheets and the report.
"""
