#include "arcplan/robot/srdf.h"

#include <fstream>
#include <sstream>

#include "arcplan/common/error.h"
#include "xml_text.h"

namespace arcplan::robot {

std::vector<DisabledCollision> parseSrdfDisabledCollisions(const std::string& srdfXml,
                                                           const std::filesystem::path& sourceFile) {
  const std::string name = sourceFile.empty() ? std::string("SRDF") : sourceFile.string();
  TiXmlDocument document;
  detail::parseXml(srdfXml, name, document);
  const TiXmlElement* root = document.RootElement();
  if (root == nullptr || std::string(root->Value()) != "robot") {
    throw Error(name + ":" + std::to_string(root ? root->Row() : 1) + ": expected an SRDF with root element <robot>");
  }
  std::vector<DisabledCollision> pairs;
  for (const TiXmlElement* element = root->FirstChildElement("disable_collisions"); element != nullptr;
       element = element->NextSiblingElement("disable_collisions")) {
    DisabledCollision pair;
    pair.line = element->Row();
    const char* link1 = element->Attribute("link1");
    const char* link2 = element->Attribute("link2");
    if (link1 == nullptr || link2 == nullptr || *link1 == '\0' || *link2 == '\0') {
      throw Error(name + ":" + std::to_string(pair.line) + ": <disable_collisions> needs link1 and link2");
    }
    pair.link1 = link1;
    pair.link2 = link2;
    if (const char* reason = element->Attribute("reason")) pair.reason = reason;
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

std::vector<DisabledCollision> loadSrdfDisabledCollisions(const std::filesystem::path& srdfFile) {
  std::ifstream in(srdfFile, std::ios::binary);
  if (!in || std::filesystem::is_directory(srdfFile)) throw Error("cannot open SRDF file " + srdfFile.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parseSrdfDisabledCollisions(text.str(), std::filesystem::absolute(srdfFile));
}

}  // namespace arcplan::robot
