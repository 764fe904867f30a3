"""The recipes: how the derivation engine derives each quantity the paper states.

One module per section of the paper or group of sections (:mod:`~.intro`: the abstract, Sec. 1
and 2; :mod:`~.sec3`; :mod:`~.sec4`; :mod:`~.sec5_1_2`; :mod:`~.sec5_3_5`; :mod:`~.sec5_6_7`:
Sec. 5.6 and the conclusion; :mod:`~.appendices`), where the claim it serves first appears
outside the abstract and the conclusion; helpers several sections share in :mod:`~.common`. A
recipe is a function of the bench returning :class:`~rollspring.analysis.paper.types.Derived`.
"""
