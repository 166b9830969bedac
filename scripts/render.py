# SPDX-License-Identifier: MIT
"""Render an nmm result to PNG with ParaView (the users' own viewer).

Run with pvbatch; on a machine without a display, under xvfb-run (on Debian 12, where
ParaView and the build's VTK cannot be installed together, use scripts/render_root.sh):

    xvfb-run -a pvbatch scripts/render.py out/case.pvd picture.png --field stress --component 1
    xvfb-run -a pvbatch scripts/render.py out/mesh.vtu mesh.png --field block --categorical \\
        --edges --lines out/boundary.vtp
    xvfb-run -a pvbatch scripts/render.py out/case.pvd contacts.png --categorical \\
        --points out/case.pvd

The last time step of a .pvd series is shown, its part 0 (nmm's elements); a .pvd given to
--points gives the last step's part 1 (nmm's contact points), to --lines its part 2 (the
joints and boundaries where they are at that step). Cell and point arrays are both
looked up by name. The known nmm fields get a legend with their unit (stresses in kPa or MPa
when large; --range stays in SI units). nmm's step files hold the deformed positions:
--magnify N draws the displacements N times their size; --warp F moves the points by F times
the 'displacement' point array (a Warp By Vector filter, as one would do by hand in ParaView),
so --magnify N is --warp N-1. Lines and points are drawn as read, not warped (contact
points carry no displacement), so --magnify suits pictures without them.

Colours: a range across zero gets Cool to Warm, white at zero (symmetric unless --range says
otherwise); a range of one sign gets the matching half of it (blue for compression) when the
field has a sign convention (stresses, forces) or is a component, else Turbo. Legends stand
in a column at the right: the field's (--legend none hides it), then the contact states.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ElementTree

from paraview import simple as pv  # pylint: disable=import-error

# Legend of nmm's arrays (docs/output.md): unit and component names.
FIELDS = {
    "stress": ("Pa", ["sxx", "syy", "sxy"], "tension +"),
    "principal_stresses": ("Pa", ["s1", "s2"], "tension +"),
    "displacement": ("m", ["ux", "uy", "uz"], ""),
    "velocity": ("m/s", ["vx", "vy", "vz"], ""),
    "area": ("m²", [], ""),
    "normal_force": ("N", [], "compression +"),
    "shear_force": ("N", [], ""),
    "gap": ("m", [], ""),
}
# Brewer Set3, yellows last: light colours on which edges and lines stay visible.
PALETTE = ["#8dd3c7", "#fdb462", "#bebada", "#fb8072", "#80b1d3", "#b3de69",
           "#fccde5", "#d9d9d9", "#bc80bd", "#ccebc5", "#ffed6f", "#ffffb3"]
CONTACT_STATES = [("open", "#969696"), ("sliding", "#d62728"), ("locked", "#1f5fbf")]
BLACK = [0.0, 0.0, 0.0]
# DejaVu Sans where it is installed (Debian's stand-in for VTK's Arial draws '[' as '(').
FONT_DIR = "/usr/share/fonts/truetype/dejavu"
FONT = os.path.join(FONT_DIR, "DejaVuSans.ttf")
BOLD = os.path.join(FONT_DIR, "DejaVuSans-Bold.ttf")


def font(proxy, bold=False, *prefixes):
    """Use DejaVu Sans for the text properties `prefixes` of `proxy` (when it exists)."""
    path = BOLD if bold else FONT
    if os.path.isfile(path):
        for prefix in prefixes or ("",):
            setattr(proxy, prefix + "FontFamily", "File")
            setattr(proxy, prefix + "FontFile", path)


def parse():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input", help=".pvd, .vtu or .vtp file")
    parser.add_argument("output", help="PNG file to write")
    parser.add_argument("--field", default="block", help="array to colour by (default: block)")
    parser.add_argument("--component", default="", help="component index or 'Magnitude'")
    parser.add_argument("--warp", type=float, default=0.0,
                        help="add WARP times the 'displacement' point array to the points")
    parser.add_argument("--magnify", type=float, default=0.0,
                        help="draw nmm's displacements MAGNIFY times their size (--warp MAGNIFY-1)")
    parser.add_argument("--edges", action="store_true", help="draw cell edges")
    parser.add_argument("--outline", action="store_true",
                        help="draw the outline of the blocks (the boundary of merged cells)")
    parser.add_argument("--lines", action="append", default=[],
                        help=".vtp (or .pvd: its part 2) of lines (joints, boundaries) drawn on "
                             "top in black, or a .vtu whose outline is drawn in grey (e.g. "
                             "step_000000.vtu: the start); may be repeated")
    parser.add_argument("--points", default="",
                        help=".vtp (or .pvd: its part 1) of points (contacts) drawn on top")
    parser.add_argument("--points-color", default="state",
                        help="colour of the points: an array of categories 0 open, 1 sliding, "
                             "2 locked (default 'state', when the points have it) or '#rrggbb'")
    parser.add_argument("--point-size", type=float, default=9.0, help="in pixels (default 9)")
    parser.add_argument("--window", default="",
                        help="the part of the model to show, 'x0,x1,y0,y1' in m (default: all)")
    parser.add_argument("--size", default="1200x800", help="image size WxH (default 1200x800)")
    parser.add_argument("--title", default="", help="text in the upper left corner")
    parser.add_argument("--legend", default="",
                        help="legend title (default: field and unit); 'none': no legend")
    parser.add_argument("--range", default="", help="colour range 'min,max' (SI units)")
    parser.add_argument("--categorical", action="store_true",
                        help="discrete colours (blocks, materials)")
    args = parser.parse_args()
    if args.magnify:
        args.warp = args.magnify - 1.0
    return args


def rgb(colour):
    colour = colour.lstrip("#")
    if len(colour) != 6:
        sys.exit(f"render.py: colour '#{colour}' is not #rrggbb")
    return [int(colour[i:i + 2], 16) / 255.0 for i in (0, 2, 4)]


def pvd_file(path, part):
    """The file of the last time step's part `part` in a .pvd collection."""
    entries = []
    for dataset in ElementTree.parse(path).getroot().iter("DataSet"):
        entries.append((float(dataset.get("timestep", "0")), dataset.get("part", "0"),
                        dataset.get("file")))
    if not entries:
        sys.exit(f"render.py: {path} lists no data set")
    last = max(entry[0] for entry in entries)
    files = [name for time, number, name in entries if time == last and number == str(part)]
    if not files:
        sys.exit(f"render.py: {path} has no part {part} at its last time {last:g}")
    return os.path.join(os.path.dirname(path), files[0])


def open_data(path, part=0):
    extension = os.path.splitext(path)[1].lower()
    if extension == ".pvd":
        path = pvd_file(path, part)
        extension = os.path.splitext(path)[1].lower()
    if not os.path.isfile(path):
        sys.exit(f"render.py: no such file {path}")
    if extension == ".vtu":
        reader = pv.XMLUnstructuredGridReader(FileName=[path])
    elif extension == ".vtp":
        reader = pv.XMLPolyDataReader(FileName=[path])
    else:
        sys.exit(f"render.py: cannot read {path}: expected .pvd, .vtu or .vtp")
    reader.UpdatePipeline()
    if reader.GetDataInformation().GetNumberOfPoints() == 0:
        sys.exit(f"render.py: {path} is empty or unreadable (see the messages above)")
    return reader


def association(source, name):
    if source.CellData.GetArray(name) is not None:
        return "CELLS"
    if source.PointData.GetArray(name) is not None:
        return "POINTS"
    available = [a.GetName() for a in source.CellData] + [a.GetName() for a in source.PointData]
    sys.exit(f"render.py: no array '{name}' (available: {', '.join(available)})")


def categorical(lut, values, names, colours):
    """Colour the integer `values` by `colours`, with `names` in the legend."""
    lut.InterpretValuesAsCategories = 1
    lut.AnnotationsInitialized = 1
    lut.Annotations = [item for value, name in zip(values, names) for item in (str(value), name)]
    lut.IndexedColors = [c for i in range(len(values)) for c in rgb(colours[i % len(colours)])]


def legend(view, lut, title, position, length):
    """Show the legend of `lut`: a vertical bar of `length` with its lower left corner at
    `position` (fractions of the picture), labels on its right, `title` above it."""
    bar = pv.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = BLACK
    bar.LabelColor = BLACK
    bar.TitleFontSize = 20
    bar.LabelFontSize = 18
    font(bar, True, "Title")
    font(bar, False, "Label")
    bar.ScalarBarThickness = 20
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Vertical"
    bar.Position = position
    bar.ScalarBarLength = length
    bar.HorizontalTitle = 1
    bar.RangeLabelFormat = "%.3g"
    if lut.InterpretValuesAsCategories:  # the names on the right, away from the model
        bar.TextPosition = "Ticks left/bottom, annotations right/top"
    bar.Visibility = 1
    return bar


def colour_field(args, view, data, shown):
    """Colour `shown` by --field; return the legend's title ('' for none) and the display."""
    where = association(data, args.field)
    array = (data.CellData if where == "CELLS" else data.PointData).GetArray(args.field)
    unit, names, sign = FIELDS.get(args.field, ("", [], ""))
    component = args.component
    if component.isdigit() and int(component) >= array.GetNumberOfComponents():
        sys.exit(f"render.py: '{args.field}' has {array.GetNumberOfComponents()} components")
    if array.GetNumberOfComponents() == 1:
        component = ""
    label = args.field
    if component.isdigit():
        label = names[int(component)] if int(component) < len(names) else \
            f"{args.field} [{component}]"
    elif component:
        label = f"|{args.field}|"
    if args.categorical:
        display = pv.Show(shown, view)
        pv.ColorBy(display, (where, args.field))
        low, high = (int(round(v)) for v in array.GetRange(0))
        values = list(range(low, high + 1))
        categorical(pv.GetColorTransferFunction(args.field), values,
                    [str(v) for v in values], PALETTE)
        display.SetScalarBarVisibility(view, False)
        # A legend only when its entries are few enough to read.
        return (args.legend or args.field) if len(values) <= len(PALETTE) else "", display
    # Scale pascals and newtons to a readable prefix through a Python Calculator.
    scale, prefix = 1.0, ""
    low, high = array.GetRange(int(component) if component.isdigit() else -1)
    if args.range:
        low, high = (float(v) for v in args.range.split(","))
    if unit in ("Pa", "N"):
        for factor, name in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
            if max(abs(low), abs(high)) >= factor:
                scale, prefix = factor, name
                break
    name = label.strip("|") + (" magnitude" if component and not component.isdigit() else "")
    if scale != 1.0 or component:
        if component.isdigit():
            expression = f"{args.field}[:, {component}] / {scale!r}"
        elif component:
            expression = f"mag({args.field}) / {scale!r}"
        else:
            expression = f"{args.field} / {scale!r}"
        shown = pv.PythonCalculator(Input=shown, Expression=expression, ArrayName=name,
                                    ArrayAssociation="Cell Data" if where == "CELLS"
                                    else "Point Data")
    display = pv.Show(shown, view)
    pv.ColorBy(display, (where, name if (scale != 1.0 or component) else args.field))
    lut = pv.GetColorTransferFunction(name if (scale != 1.0 or component) else args.field)
    lut.AutomaticRescaleRangeMode = "Never"
    if low < 0.0 < high:  # signed: diverging colours, white at zero
        lut.ApplyPreset("Cool to Warm", True)
        if not args.range:
            low, high = -max(-low, high), max(-low, high)
    elif sign or component.isdigit():  # one sign: the half of Cool to Warm, white at zero
        lut.ApplyPreset("Cool to Warm", True)
        points = lut.RGBPoints  # value, r, g, b each; the middle point is the light grey
        middle = len(points) // 8 * 4
        lut.RGBPoints = points[:middle + 4] if high <= 0.0 else points[middle:]
        if not args.range:
            low, high = min(low, 0.0), max(high, 0.0)
    else:
        lut.ApplyPreset("Turbo", True)
    lut.RescaleTransferFunction(low / scale, high / scale)
    title = args.legend or label + (f" ({prefix}{unit})" if unit else "") + \
        (f"\n({sign})" if sign else "")
    return title, display


def outline(source, warp=0.0):
    """The boundary edges of `source`'s cells (its blocks' outlines), warped by `warp`."""
    if source.CellData.GetArray("block") is not None:
        # Each block at z = its id, so that blocks touching along a joint keep their edges
        # there. nmm's cells have their own points: the points take their cell's block id.
        source = pv.Calculator(Input=pv.CellDatatoPointData(Input=source),
                               AttributeType="Point Data", ResultArrayName="apart",
                               Function="coordsX*iHat + coordsY*jHat + block*kHat",
                               CoordinateResults=1)
    # Merge the cells' points, so that only the free edges (outline and cracks) remain.
    merged = pv.Clean(Input=pv.ExtractSurface(Input=source), Tolerance=1e-7, PointMerging=1,
                      ConvertLinesToPoints=0, ConvertPolysToLines=0, ConvertStripsToPolys=0)
    if warp != 0.0:
        merged = pv.WarpByVector(Input=merged, Vectors=["POINTS", "displacement"],
                                 ScaleFactor=warp)
    edges = pv.FeatureEdges(Input=merged, BoundaryEdges=1, FeatureEdges=0, NonManifoldEdges=0,
                            ManifoldEdges=0)
    flat = pv.Transform(Input=edges)  # back to z = 0
    flat.Transform.Scale = [1.0, 1.0, 0.0]
    return flat


def draw_lines(view, source, lift, colour, width):
    """Show `source` in one colour, `lift` above the model so that it is not hidden."""
    lifted = pv.Transform(Input=source)
    lifted.Transform.Translate = [0.0, 0.0, lift]
    shown = pv.Show(lifted, view)
    shown.ColorArrayName = ["POINTS", ""]
    shown.DiffuseColor = colour
    shown.AmbientColor = colour
    shown.LineWidth = width


def grow(bounds, source):
    """Grow the box `bounds` (x0, x1, y0, y1, z0, z1) to hold `source`."""
    box = source.GetDataInformation().GetBounds()
    for b in range(0, 6, 2):
        bounds[b], bounds[b + 1] = min(bounds[b], box[b]), max(bounds[b + 1], box[b + 1])


def main():
    args = parse()
    width, height = (int(v) for v in args.size.split("x"))
    data = open_data(args.input)
    shown = data
    if args.warp != 0.0:
        if data.PointData.GetArray("displacement") is None:
            sys.exit(f"render.py: {args.input} has no 'displacement' point array to warp by")
        shown = pv.WarpByVector(Input=data, Vectors=["POINTS", "displacement"],
                                ScaleFactor=args.warp)
    view = pv.CreateView("RenderView")
    view.ViewSize = [width, height]
    view.Background = [1.0, 1.0, 1.0]
    view.OrientationAxesVisibility = 0
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    title, display = colour_field(args, view, data, shown)
    display.Representation = "Surface With Edges" if args.edges else "Surface"
    display.EdgeColor = [0.3, 0.3, 0.3]
    display.Ambient, display.Diffuse = 1.0, 0.0  # a flat picture: the colours unshaded
    bounds = list(shown.GetDataInformation().GetBounds())
    lift = 1e-3 * max(bounds[1] - bounds[0], bounds[3] - bounds[2])  # above the surface
    if args.outline:
        draw_lines(view, outline(data, args.warp), lift, [0.15, 0.15, 0.15], 1.5)
    legends = []  # (lookup table, title)
    if title and args.legend != "none":
        legends.append((pv.GetColorTransferFunction(display.ColorArrayName[1]), title))
    for path in args.lines:
        lines = open_data(path, part=2)
        if path.lower().endswith(".vtu"):  # e.g. the start of a run, drawn over the last step
            draw_lines(view, outline(lines), lift, [0.55, 0.55, 0.55], 2.0)
        else:
            draw_lines(view, lines, lift, BLACK, 2.5)
        grow(bounds, lines)
    if args.points:
        points = open_data(args.points, part=1)
        lifted = pv.Transform(Input=points)
        lifted.Transform.Translate = [0.0, 0.0, 2.0 * lift]
        point_display = pv.Show(lifted, view)
        point_display.Representation = "Points"
        point_display.PointSize = args.point_size
        # Flat squares, not spheres: in the Debian 12 root of 2026-12-01 (Mesa llvmpipe)
        # ParaView 5.11's sphere impostors are drawn behind the surface they lie on.
        point_display.RenderPointsAsSpheres = 0
        point_display.Ambient, point_display.Diffuse = 1.0, 0.0  # flat: the legend's colours
        by_array = points.PointData.GetArray(args.points_color) is not None
        if args.points_color.startswith("#") or not by_array:
            colour = args.points_color if args.points_color.startswith("#") else "#d62728"
            point_display.ColorArrayName = ["POINTS", ""]
            point_display.DiffuseColor = rgb(colour)
            point_display.AmbientColor = rgb(colour)
        else:
            pv.ColorBy(point_display, ("POINTS", args.points_color))
            point_display.SetScalarBarVisibility(view, False)
            lut = pv.GetColorTransferFunction(args.points_color)
            categorical(lut, [0, 1, 2], [s[0] for s in CONTACT_STATES],
                        [s[1] for s in CONTACT_STATES])
            legends.append((lut, "contacts"))
        grow(bounds, points)
    # Layout in fractions of the picture: the model at the left, below the title and above
    # the note; the legends in a column at the right, stacked from the top.
    right = 0.83 if legends else 0.98
    top = 0.91 if args.title else 0.97
    bottom = 0.07 if args.warp != 0.0 else 0.03
    heights = []  # of each legend's bar; a continuous one takes the room left
    for lut, text in legends:
        entries = len(lut.Annotations) // 2
        heights.append(0.055 * entries if lut.InterpretValuesAsCategories else 0.0)
    titles = [0.035 * (text.count("\n") + 1) + 0.025 for _, text in legends]
    free = top - 0.03 - sum(heights) - sum(titles) - 0.04 * (len(legends) - 1)
    above = top
    for (lut, text), length, title_height in zip(legends, heights, titles):
        length = length or min(0.7, max(0.25, free))
        above -= title_height
        legend(view, lut, text, [right + 0.03, above - length], length)
        above -= length + 0.04
    if args.title:
        title_text = pv.Text(Text=args.title)
        title_display = pv.Show(title_text, view)
        title_display.Color = BLACK
        title_display.WindowLocation = "Upper Left Corner"
        title_display.FontSize = 24
        font(title_display)
    if args.warp != 0.0:
        note = pv.Text(Text=f"displacements \u00d7 {args.warp + 1.0:g}")
        note_display = pv.Show(note, view)
        note_display.Color = [0.3, 0.3, 0.3]
        note_display.WindowLocation = "Lower Left Corner"
        note_display.FontSize = 18
        font(note_display)
    view.InteractionMode = "2D"
    # Fit the data's box (or the window) into the free part of the picture.
    x0, x1, y0, y1 = bounds[:4]
    if args.window:
        x0, x1, y0, y1 = (float(v) for v in args.window.split(","))
    left = 0.02
    aspect = width / height
    scale = 1.04 * max((y1 - y0) / 2.0 / (top - bottom),
                       (x1 - x0) / 2.0 / aspect / (right - left))
    world_width = 2.0 * scale * aspect
    centre_x = (x0 + x1) / 2.0 - ((left + right) / 2.0 - 0.5) * world_width
    centre_y = (y0 + y1) / 2.0 - ((bottom + top) / 2.0 - 0.5) * 2.0 * scale
    view.CameraFocalPoint = [centre_x, centre_y, 0.0]
    view.CameraPosition = [centre_x, centre_y, 10.0 * max(x1 - x0, y1 - y0, 1.0)]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = scale
    pv.SaveScreenshot(args.output, view, ImageResolution=[width, height],
                      TransparentBackground=0, CompressionLevel="9")
    print(f"render.py: wrote {args.output}")


if __name__ == "__main__":
    main()
