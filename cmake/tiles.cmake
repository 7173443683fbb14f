# Filled in by the tiles work (see issues).
