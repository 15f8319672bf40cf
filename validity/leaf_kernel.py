"""The decorator of the compiled kernels that allocate nothing: numba's ``@njit(cache=True)``
without its runtime's reference counting (``_nrt=False``).

Numba counts references to arrays with atomic instructions: a call to a compiled function
that LLVM does not inline increfs and decrefs each array argument, and every view
(``verts[p]``) is counted too. A contact search makes dozens of such calls a step: on the
feeder's drops they were a third of the dynamic level's time (measured with perf: 36% of the
samples in ``NRT_incref``/``NRT_decref``). A kernel that takes arrays and writes into them
needs no counting; one that allocates cannot be compiled this way (numba refuses), so the
decorator can only be put where it is safe.
"""

from __future__ import annotations

from typing import Any, cast

from numba import njit

leaf_kernel = cast(Any, njit)(cache=True, _nrt=False)  # _nrt: numba's, not in its type stubs
"""``@leaf_kernel`` on a compiled function that allocates no array (and calls none that
does): the same code as ``@njit(cache=True)``, without reference counting."""
