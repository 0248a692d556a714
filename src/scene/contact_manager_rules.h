// The contact manager's choice of a response for each pair of collision models: SOFA's
// CollisionResponse gives every pair its `response`; RuleBasedContactManager first tries its ordered
// rules (collision/response/contact/RuleBasedContactManager.h in SOFA). A model's own
// contactResponse comes before both. Internal to src/scene (collision_builder.cpp).
#pragma once

#include "scene_data.h"

#include <string>
#include <vector>

namespace fastcorot::scene_detail {

// What a rule or the manager needs to know of one collision model.
struct ContactModelIdentity {
  std::string name;              // SOFA's name of the component
  std::vector<int> groups;       // its `group` numbers
  std::string contact_response;  // its own contactResponse, empty for none
};

class ContactManagerRules {
 public:
  // Reads `manager` (a CollisionResponse, DefaultContactManager or RuleBasedContactManager): its
  // response, and for the rule-based one its rules (three words each: two model words, a response;
  // words left over after the last whole rule are warned and ignored, as SOFA's reader drops them) and
  // its variables (each an attribute of the manager).
  ContactManagerRules(SceneData& data, Component& manager);

  // The response of the pair (model1, model2) as SOFA's contact factory reads it: a response name,
  // then optionally '?' and its parameters (name=value joined by '&'). The manager's response carries
  // its responseParams so. CollisionResponse: the models' own contactResponse when only one has one
  // or both agree, else the manager's. RuleBasedContactManager: model1's own, else model2's, else the
  // first rule that matches the pair either way round, else the manager's. $name$ in a rule's or the
  // manager's response is the variable's value (replaced once, when read; an unknown variable is
  // warned and replaced by nothing, as SOFA).
  std::string response(const ContactModelIdentity& model1, const ContactModelIdentity& model2) const;

  const std::string& default_response() const { return default_response_; }

 private:
  struct Rule {
    // A model word: a name, "*" (any model), or a group number (name empty).
    struct Word {
      std::string name;
      int group = 0;
      bool matches(const ContactModelIdentity& model) const;
    };
    Word first, second;
    std::string response;
  };
  std::string substituted(const std::string& response) const;

  SceneData& data_;
  Component& manager_;
  std::string default_response_;
  std::vector<Rule> rules_;
  std::vector<std::string> variables_;
  bool rule_based_ = false;
};

}  // namespace fastcorot::scene_detail
