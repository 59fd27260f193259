/* View of hogeweg-1.31a.l: 360/16 = 22.5 degrees. */
angle factor: 16
