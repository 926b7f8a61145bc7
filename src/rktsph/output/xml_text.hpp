// Escaping of text placed inside XML attribute values (VTU array names, PVD file names).
#pragma once

#include <string>
#include <string_view>

namespace rktsph {

/// Replaces & < > " ' by their entities so that any name stays a well-formed attribute value.
std::string escape_xml_attribute(std::string_view text);

}  // namespace rktsph
