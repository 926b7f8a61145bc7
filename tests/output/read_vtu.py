#!/usr/bin/python3
"""Independent reader for the VTK XML files written by rktsph, used by the output tests.

    read_vtu.py FILE.vtu      prints every array of an UnstructuredGrid as JSON
    read_vtu.py --pvd FILE    prints the DataSet entries of a collection, in file order, as JSON

It uses only xml.etree, base64, struct and json, and decodes the inline binary format from the
VTK file-format description rather than from rktsph's code, so that a mistake in the writer
shows up as a mismatch. Any departure from the expected layout is an error (exit status 1).
"""

import base64
import json
import struct
import sys
import xml.etree.ElementTree as ElementTree

VALUE_FORMATS = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i", "UInt8": "B",
                 "UInt32": "I", "UInt64": "Q"}
HEADER_FORMATS = {"UInt64": "Q", "UInt32": "I"}


class FormatError(Exception):
    pass


def require(condition, message):
    if not condition:
        raise FormatError(message)


def decode_array(element, header_type, expected_tuples):
    """Decodes one binary DataArray; checks its byte count against the declared sizes."""
    array_type = element.get("type")
    require(array_type in VALUE_FORMATS, f"unsupported DataArray type {array_type!r}")
    require(element.get("format") == "binary", "DataArray is not format=\"binary\"")
    components = int(element.get("NumberOfComponents", "1"))
    raw = base64.b64decode("".join((element.text or "").split()), validate=True)
    header_code = HEADER_FORMATS[header_type]
    header_size = struct.calcsize("<" + header_code)
    require(len(raw) >= header_size, "binary block shorter than its header")
    (byte_count,) = struct.unpack_from("<" + header_code, raw, 0)
    payload = raw[header_size:]
    require(byte_count == len(payload),
            f"header says {byte_count} bytes, block holds {len(payload)}")
    value_size = struct.calcsize("<" + VALUE_FORMATS[array_type])
    value_count = expected_tuples * components
    require(byte_count == value_count * value_size,
            f"array {element.get('Name')!r}: {byte_count} bytes for {value_count} values")
    values = list(struct.unpack("<%d%s" % (value_count, VALUE_FORMATS[array_type]), payload))
    # ComponentName<i> is how VTK's XML readers (and so ParaView) name component i.
    names = [element.get(f"ComponentName{i}") for i in range(components)]
    return {"type": array_type, "components": components, "component_names": names,
            "values": values}


def read_vtu(path):
    root = ElementTree.parse(path).getroot()
    require(root.tag == "VTKFile", "root element is not VTKFile")
    require(root.get("type") == "UnstructuredGrid", "VTKFile type is not UnstructuredGrid")
    require(root.get("byte_order") == "LittleEndian", "byte_order is not LittleEndian")
    header_type = root.get("header_type", "UInt32")
    require(header_type in HEADER_FORMATS, f"unsupported header_type {header_type!r}")
    pieces = root.findall("./UnstructuredGrid/Piece")
    require(len(pieces) == 1, f"expected one Piece, found {len(pieces)}")
    piece = pieces[0]
    point_count = int(piece.get("NumberOfPoints"))
    cell_count = int(piece.get("NumberOfCells"))

    points = piece.findall("./Points/DataArray")
    require(len(points) == 1, "Points must hold exactly one DataArray")
    result = {
        "header_type": header_type,
        "NumberOfPoints": point_count,
        "NumberOfCells": cell_count,
        "Points": decode_array(points[0], header_type, point_count),
        "Cells": {},
        "PointData": {},
    }
    require(result["Points"]["components"] == 3, "Points must have 3 components")
    for name in ("connectivity", "offsets", "types"):
        found = piece.findall(f"./Cells/DataArray[@Name='{name}']")
        require(len(found) == 1, f"Cells must hold exactly one {name} array")
        # Connectivity length is the sum of the cell sizes, only known once offsets are read;
        # for the vertex cells written here it equals the number of cells.
        result["Cells"][name] = decode_array(found[0], header_type, cell_count)
    for element in piece.findall("./PointData/DataArray"):
        name = element.get("Name")
        require(name not in result["PointData"], f"duplicate point-data name {name!r}")
        result["PointData"][name] = decode_array(element, header_type, point_count)
    return result


def read_pvd(path):
    root = ElementTree.parse(path).getroot()
    require(root.tag == "VTKFile", "root element is not VTKFile")
    require(root.get("type") == "Collection", "VTKFile type is not Collection")
    collections = root.findall("./Collection")
    require(len(collections) == 1, "expected one Collection element")
    datasets = []
    for element in collections[0]:
        require(element.tag == "DataSet", f"unexpected element {element.tag!r} in Collection")
        datasets.append({"timestep": float(element.get("timestep")), "file": element.get("file")})
    return {"datasets": datasets}


def main(arguments):
    if len(arguments) == 2 and arguments[0] == "--pvd":
        result = read_pvd(arguments[1])
    elif len(arguments) == 1:
        result = read_vtu(arguments[0])
    else:
        print(__doc__, file=sys.stderr)
        return 2
    # allow_nan=False: NaN is not JSON, and the test data contain none.
    print(json.dumps(result, allow_nan=False))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except (FormatError, ElementTree.ParseError, ValueError, struct.error) as error:
        print(f"read_vtu.py: {error}", file=sys.stderr)
        sys.exit(1)
