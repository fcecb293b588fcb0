#pragma once
/// What the two X3D encodings need to know of a field to move its value
/// between them (ISO/IEC 19776-1 XML, 19776-2 classic): the XML encoding
/// writes every value as attribute text, unbracketed and with `true`/`false`,
/// strings of an SFString unquoted; the classic encoding brackets lists and
/// quotes every string. Which is which depends on the field's type, given
/// here for the fields the reader types (read_vrml97.h), the string fields of
/// the standard nodes, and the multi-component single values; other fields
/// are told by their value's form.
#include <string>
#include <string_view>

namespace lodforge::vrml97 {

enum class ValueShape {
  kUnknown,    ///< not known: told by the value's form
  kSFString,   ///< one string: XML unquoted, classic quoted
  kMFString,   ///< strings, each quoted in both
  kSFNumbers,  ///< one value of several numbers (SFVec3f, SFRotation, SFImage...): never bracketed
  kMFNumbers,  ///< a list of numbers or booleans: bracketed in classic
  kNode,       ///< SFNode / MFNode
};

/// The shape of field `field` of a node of type `node_type`.
ValueShape x3d_value_shape(std::string_view node_type, std::string_view field);

/// The shape of a value of the declared type `type_name` ("SFString",
/// "MFVec3f", ...); kUnknown for a name that is no field type.
ValueShape shape_of_type(std::string_view type_name);

/// The field of its parent a node of type `node_type` fills when the XML
/// encoding does not say (its default containerField): "geometry" for
/// geometry nodes, "appearance", "material", "texture", "coord", ...,
/// "children" for the rest.
std::string_view default_container_field(std::string_view node_type);

/// The value of a field of declared type `type_name` that the XML encoding
/// leaves out, in the classic encoding ("0 0 0" for SFVec3f, FALSE, "" for
/// SFString, [] for any MF type, NULL for SFNode).
std::string default_classic_value(std::string_view type_name);

/// True if the attribute token `t` is read as a number (as the classic
/// reader's number parser takes it: a digit, sign or point first, or inf /
/// nan / infinity).
bool is_number_token(std::string_view t);

/// True if the attribute token `t` is a boolean (true / false, either case
/// of the encodings).
bool is_bool_token(std::string_view t);

/// `text` as a classic-encoding string literal: quoted, with `"` and `\` escaped.
std::string quote_classic(std::string_view text);

}  // namespace lodforge::vrml97
