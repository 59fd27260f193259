VERSION stedit
0 1 0 1 0 0
PRECISION S: 4 T: 4
CONTACT POINT X:0 Y:0 Z:0
END POINT X : 0 Y : 1 Z : 0
heading x: 0 y: 1 z: 0
UP X: 0 Y: 0 Z: 1
SIZE: 1
p
TOP COLOR: 1 DIFFUSE: 0.8 BOTTOM COLOR: 2 DIFFUSE: .5
AL: ~ ~ A: ~ ~ AR: ~ ~
L: ~ ~ R: ~ ~
BL: ~ ~ B: ~ ~ BR: ~ ~
0 0 0  .33 0 0  .66 0 0  1 0 0
0 .33 0  .33 .33 1e-1  .66 .33 +0.1  1 .33 0
0 .66 0  .33 .66 0.1  .66 .66 0.1  1 .66 0
0 1 0  .33 1 0  .66 1 0  1 1 0
