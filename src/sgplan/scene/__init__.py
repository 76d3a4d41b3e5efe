"""Scene graph: the building model, its loaders and writers, the occupancy grid and the labels."""
