#pragma once
// XML text (URDF, SRDF) parsed with TinyXML, urdfdom's own parser, after a UTF-8 check TinyXML needs.
// Internal to arcplan::robot.
#include <string>

#include <tinyxml.h>

namespace arcplan::robot::detail {

// Parses `text` into `document`; throws arcplan::Error "<sourceName>:<line>[:<column>]: ..." for text
// that is not UTF-8 or not well-formed XML.
void parseXml(const std::string& text, const std::string& sourceName, TiXmlDocument& document);

}  // namespace arcplan::robot::detail
