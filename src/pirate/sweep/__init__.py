"""One sweep runner for every twin bench.

A bench declares its cases (:class:`pirate.sweep.cases.Sweep`: a table of
parameters, a seed each) and a function that runs one case in a fresh twin
and returns its record's fields; the runner (:mod:`pirate.sweep.cli`) runs
the cases on a Dask cluster, each in a process of its own, appends the
records to one JSON Lines file per sweep as they finish, resumes an
interrupted sweep and prints the table (:mod:`pirate.sweep.report`).

Pure parts (no Dask): :mod:`.cases`, :mod:`.records`, :mod:`.report`,
:mod:`.progress`, :mod:`.runner`; the process edge :mod:`.child`; the Dask
edge :mod:`.engine`. How to run a sweep: doc/sweeps.md.
"""
