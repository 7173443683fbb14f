# Filled in by the lattice work (see issues).
