# SPDX-License-Identifier: MIT
"""Render an nmm result to PNG with ParaView (the users' own viewer).

Run with pvbatch; on a machine without a display, under xvfb-run:

    xvfb-run -a pvbatch scripts/render.py out/case.pvd picture.png --field stress --component 1
    xvfb-run -a pvbatch scripts/render.py out/mesh.vtu mesh.png --field block --edges \\
        --lines out/boundary.vtp

The last time step of a .pvd series is shown. Cell and point arrays are both looked up by
name; --warp scales the 'displacement' point array (a Warp By Vector filter, as one would
do by hand in ParaView).
"""
import argparse
import os
import sys

from paraview import simple as pv  # pylint: disable=import-error


def parse():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input", help=".pvd, .vtu or .vtp file")
    parser.add_argument("output", help="PNG file to write")
    parser.add_argument("--field", default="block", help="array to colour by (default: block)")
    parser.add_argument("--component", default="", help="component index or 'Magnitude'")
    parser.add_argument("--warp", type=float, default=0.0,
                        help="scale factor of the 'displacement' point array (0: none)")
    parser.add_argument("--edges", action="store_true", help="draw cell edges")
    parser.add_argument("--lines", action="append", default=[],
                        help=".vtp of lines (joints, boundaries) drawn on top in black")
    parser.add_argument("--points", default="", help=".vtp of points (contacts) drawn on top")
    parser.add_argument("--size", default="1600x1000", help="image size WxH")
    parser.add_argument("--title", default="", help="text in the upper left corner")
    parser.add_argument("--range", default="", help="colour range 'min,max'")
    parser.add_argument("--categorical", action="store_true",
                        help="discrete colours (blocks, materials)")
    return parser.parse_args()


def open_data(path):
    extension = os.path.splitext(path)[1].lower()
    if extension == ".pvd":
        reader = pv.PVDReader(FileName=path)
    elif extension == ".vtu":
        reader = pv.XMLUnstructuredGridReader(FileName=[path])
    elif extension == ".vtp":
        reader = pv.XMLPolyDataReader(FileName=[path])
    else:
        sys.exit(f"render.py: cannot read {path}: expected .pvd, .vtu or .vtp")
    times = reader.TimestepValues
    if times:
        last = times[-1] if isinstance(times, (list, tuple)) else times
        pv.GetAnimationScene().AnimationTime = last
        reader.UpdatePipeline(last)
    else:
        reader.UpdatePipeline()
    return reader


def association(source, name):
    info = source.GetDataInformation().DataInformation
    if source.CellData.GetArray(name) is not None:
        return "CELLS"
    if source.PointData.GetArray(name) is not None:
        return "POINTS"
    available = [a.GetName() for a in source.CellData] + [a.GetName() for a in source.PointData]
    del info
    sys.exit(f"render.py: no array '{name}' (available: {', '.join(available)})")


def main():
    args = parse()
    width, height = (int(v) for v in args.size.split("x"))
    data = open_data(args.input)
    shown = data
    if args.warp != 0.0:
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
    display = pv.Show(shown, view)
    display.Representation = "Surface With Edges" if args.edges else "Surface"
    display.EdgeColor = [0.25, 0.25, 0.25]
    where = association(data, args.field)
    if args.component:
        pv.ColorBy(display, (where, args.field, args.component))
    else:
        pv.ColorBy(display, (where, args.field))
    lut = pv.GetColorTransferFunction(args.field)
    if args.categorical:
        lut.ApplyPreset("Brewer Qualitative Set3", True)
        lut.InterpretValuesAsCategories = 0
        lut.NumberOfTableValues = 12
        lut.Discretize = 1
    else:
        lut.ApplyPreset("Turbo", True)
    if args.range:
        low, high = (float(v) for v in args.range.split(","))
        lut.RescaleTransferFunction(low, high)
    else:
        display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, not args.categorical)
    if not args.categorical:
        bar = pv.GetScalarBar(lut, view)
        bar.TitleColor = [0, 0, 0]
        bar.LabelColor = [0, 0, 0]
        bar.Title = args.field + (f" [{args.component}]" if args.component else "")
        bar.ComponentTitle = ""
    for path in args.lines:
        lines = open_data(path)
        line_display = pv.Show(lines, view)
        line_display.DiffuseColor = [0.0, 0.0, 0.0]
        line_display.AmbientColor = [0.0, 0.0, 0.0]
        line_display.LineWidth = 2.5
        line_display.ColorArrayName = ["POINTS", ""]
    if args.points:
        points = open_data(args.points)
        point_display = pv.Show(points, view)
        point_display.Representation = "Points"
        point_display.PointSize = 6
        point_display.DiffuseColor = [0.8, 0.0, 0.0]
        point_display.ColorArrayName = ["POINTS", ""]
    if args.title:
        text = pv.Text(Text=args.title)
        text_display = pv.Show(text, view)
        text_display.Color = [0.0, 0.0, 0.0]
        text_display.WindowLocation = "Upper Left Corner"
        text_display.FontSize = 14
        view.InteractionMode = "2D"
    pv.ResetCamera(view)
    # Fit the data's box, not its bounding sphere (ResetCamera leaves wide margins in 2D).
    x0, x1, y0, y1, _, _ = shown.GetDataInformation().GetBounds()
    centre = [(x0 + x1) / 2.0, (y0 + y1) / 2.0]
    view.CameraFocalPoint = [centre[0], centre[1], 0.0]
    view.CameraPosition = [centre[0], centre[1], 1.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraParallelProjection = 1
    aspect = width / height
    view.CameraParallelScale = 1.08 * max((y1 - y0) / 2.0, (x1 - x0) / 2.0 / aspect)
    pv.SaveScreenshot(args.output, view, ImageResolution=[width, height])
    print(f"render.py: wrote {args.output}")


if __name__ == "__main__":
    main()
