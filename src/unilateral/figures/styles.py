"""The styles of the model figures (2-D: :mod:`.model`, 3-D: :mod:`.model3d`): one look for each kind of element."""

#: Style of each element kind: legend label, colour, line style, line width.
KIND_STYLES = {
    "beam": ("beam", "0.15", "-", 2.0),
    "bar": ("bar", "C0", "-", 1.0),
    "rigid_link": ("rigid link", "0.6", "-", 3.5),
    "spring": ("spring", "C2", (0, (4, 2)), 1.1),
    "dashpot": ("dashpot", "C8", "-.", 1.1),
    "cable": ("cable (tension only)", "C1", (0, (1, 1.5)), 1.4),
    "gap": ("gap (pounding link)", "C3", (0, (3, 1, 1, 1)), 1.4),
    "soil": ("soil spring (compression only)", "C5", "-", 1.3),
    "yield": ("yielding link", "C4", "-", 1.5),
    "slider": ("slider", "C9", "-", 1.5),
}
#: Length of the symbol of an element to the ground, as a fraction of the structure's size.
GROUND_SYMBOL = 0.06
