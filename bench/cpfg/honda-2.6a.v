/* View of honda-2.6a.l: Honda's tree is drawn in 3D with lines as wide as !(w) says. */
angle increment: 45
initial line width: 1 pixels
