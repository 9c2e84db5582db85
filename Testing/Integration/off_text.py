"""An .off surface as its text: the points' coordinates as written (so that other formats
written from them hold the very same doubles) and the polygons' point ids."""


def read_off(path):
    rows = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].split()
            if line:
                rows.append(line)
    header = rows[0]
    counts = header[1:] if len(header) > 1 else rows[1]
    start = 1 if len(header) > 1 else 2
    n, m = int(counts[0]), int(counts[1])
    points = [tuple(rows[start + i][:3]) for i in range(n)]  # text, as written
    polygons = [[int(x) for x in rows[start + n + f][1:1 + int(rows[start + n + f][0])]]
                for f in range(m)]
    return points, polygons
