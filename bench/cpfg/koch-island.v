/* View of koch-island.l: the angle the turtle turns by. */
angle increment: 90
