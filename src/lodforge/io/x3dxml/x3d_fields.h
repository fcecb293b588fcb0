#pragma once
/// What the X3D XML encoding leaves to the reader's knowledge of the node
/// types, shared by the X3D XML reader and writer: which field a child element
/// goes to when it names none (containerField), and which fields hold one
/// value although the value has several numbers or no quotes.
#include <string_view>

namespace lodforge::x3dxml::detail {

/// The field a child of type `child` goes to inside a node of type `parent`
/// when it gives no containerField (ISO/IEC 19776-1, the containerField
/// defaults of each node type; "children" for any type not listed).
std::string_view default_container(std::string_view child, std::string_view parent);

/// True if field `field` of `parent` holds one node (SFNode): written as
/// `field Node {}`, not `field [ ... ]`, in the classic encoding.
bool single_node_field(std::string_view parent, std::string_view field);

/// True if field `field` is a single vector, rotation, colour or image
/// (several numbers, one value): no brackets in the classic encoding.
bool single_vector_field(std::string_view parent, std::string_view field);

/// True if field `field` of `parent` is an SFString: unquoted in XML, quoted
/// in the classic encoding.
bool single_string_field(std::string_view parent, std::string_view field);

}  // namespace lodforge::x3dxml::detail
