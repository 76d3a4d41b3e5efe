"""The process and runtime helpers of sgplan's own processes (the console script, a bench worker, the
mission service): numba's kernel cache and BLAS probe (:mod:`~sgplan.runtime.jit`), the C allocator's
handling of freed memory (:mod:`~sgplan.runtime.malloc`), and setting up and ending such a process
(:mod:`~sgplan.runtime.process`).

It sits below every front end (``cli``, ``commands``, ``bench``, ``serve``) and above the compiled kernels
whose cache it inspects, so that each front end imports it and none imports another.
"""
