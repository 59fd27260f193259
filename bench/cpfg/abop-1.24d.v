/* View of abop-1.24d.l. */
angle increment: 20
