"""Planning: the hierarchical domain, heuristics, AMRA*, compiled kernels, the path checker."""
