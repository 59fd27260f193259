/* View file of cpfg-generalized-cylinder.l: the contour of its cylinders. */
contour sides: 30
contour: 1 cpfg-generalized-cylinder.con
initial line width: 2
