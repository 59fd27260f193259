0/* a view with most settings */
angle increment: 22.5
angle factor: 2
initial line width: 2 pixels
line width increment: 1
initial color: 3
color increment: 2
contour sides: 12
tropism direction: 0 -1 0
initial elasticity: 0.2
elasticity increment: 0.05
torque: 0 0 1
twist: 30
viewpoint: 0 0 10
view reference point: 0 0 0
up vector: 0 1 0
projection: perspective
render mode: shaded
line style: cylinder
surface: l leaf.s 1 4 4
box: -1 1 -1 1 -1 1
light: O: 1 1 1 D: 1 1 1
scale factor: 0.9
