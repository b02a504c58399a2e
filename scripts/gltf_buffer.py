"""One glTF binary buffer being written: the bytes, their buffer views and accessors (the generators
scripts/make_animated_grid.py and scripts/make_skinned_grid.py share it)."""


class GltfBuffer:
    def __init__(self):
        self.blob = bytearray()
        self.views, self.accessors = [], []

    def add(self, data, kind, count, component=5126, target=None, minmax=None):
        """Appends `data` (4-byte aligned) as a buffer view and an accessor of `count` elements of type
        `kind`; returns the accessor's index."""
        while len(self.blob) % 4:
            self.blob.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data),
                           **({"target": target} if target else {})})
        self.blob.extend(data)
        a = {"bufferView": len(self.views) - 1, "componentType": component, "count": count, "type": kind}
        if minmax:
            a["min"], a["max"] = minmax
        self.accessors.append(a)
        return len(self.accessors) - 1
