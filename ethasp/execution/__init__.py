"""How ethasp runs work so that its limits hold and Cancel stops it.

* :mod:`ethasp.execution.limits`: time and memory limits, and the memory of
  process trees;
* :mod:`ethasp.execution.worker`: a child process that runs calls under
  limits, ended at once at a limit or on cancel; every front end runs its
  searches in one;
* :mod:`ethasp.execution.context`: the call a worker runs, as the work sees
  it (progress, partial results, cancellation);
* :mod:`ethasp.execution.spawner`: child processes for the engines, started
  safely from a process with threads;
* :mod:`ethasp.execution.symbols`: clingo's symbols pickled as text, so that
  they mean the same in another process.
"""
