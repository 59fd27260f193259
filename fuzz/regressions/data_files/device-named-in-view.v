0contour: 1 /dev/zero
surface: l /dev/zero 1
function: /dev/zero 10
