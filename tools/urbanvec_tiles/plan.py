"""Tile layout: core tiles of T x T cells, each read with a halo of H cells (clipped to the grid)."""
from dataclasses import dataclass


class UsageError(Exception):
    """A bad option value (exit 2)."""


@dataclass(frozen=True)
class Tile:
    row: int  # tile row, column (0-based)
    col: int
    core: tuple  # (c0, r0, c1, r1) cells, half-open
    grid: tuple  # (width, height) of the whole grid

    @property
    def name(self):
        return "r%03d_c%03d" % (self.row, self.col)

    def window(self, halo, boxes=()):
        """gdal_translate -srcwin of the core plus `halo` cells, clipped to the grid; with `boxes`
        (c0, r0, c1, r1: the enclosed regions the core meets, regions.py), also each box plus `halo`."""
        c0, r0, c1, r1 = self.core
        for b in boxes:
            c0, r0, c1, r1 = min(c0, b[0]), min(r0, b[1]), max(c1, b[2]), max(r1, b[3])
        w, h = self.grid
        x0, y0 = max(0, c0 - halo), max(0, r0 - halo)
        x1, y1 = min(w, c1 + halo), min(h, r1 + halo)
        return (x0, y0, x1 - x0, y1 - y0)


def plan(width, height, tile, halo):
    if tile <= 0:
        raise UsageError("-tile must be at least 1 cell, got %d" % tile)
    if halo < 0:
        raise UsageError("-halo must be 0 or more cells, got %d" % halo)
    if halo > width or halo > height:
        raise UsageError("-halo %d is larger than the grid (%d x %d cells)" % (halo, width, height))
    tiles = []
    for r, r0 in enumerate(range(0, height, tile)):
        for c, c0 in enumerate(range(0, width, tile)):
            tiles.append(Tile(r, c, (c0, r0, min(c0 + tile, width), min(r0 + tile, height)),
                              (width, height)))
    return tiles
