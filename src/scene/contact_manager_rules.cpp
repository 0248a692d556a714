#include "contact_manager_rules.h"

#include <algorithm>
#include <sstream>

namespace fastcorot::scene_detail {

namespace {

// SOFA reads a rule word made only of digits and '-' as a group number.
bool is_group_word(const std::string& word) {
  return !word.empty() && word.find_first_not_of("-0123456789") == std::string::npos;
}

}  // namespace

bool ContactManagerRules::Rule::Word::matches(const ContactModelIdentity& model) const {
  if (!name.empty()) return name == "*" || name == model.name;
  return std::find(model.groups.begin(), model.groups.end(), group) != model.groups.end();
}

ContactManagerRules::ContactManagerRules(SceneData& data, Component& manager) : data_(data), manager_(manager) {
  default_response_ = data_.text(manager, "response", "PenalityContactForceField");
  if (const std::string params = data_.text(manager, "responseParams", ""); !params.empty()) default_response_ += "?" + params;
  rule_based_ = manager.type() == "RuleBasedContactManager";
  if (!rule_based_) return;
  std::istringstream variables(data_.text(manager, "variables", ""));
  for (std::string name; variables >> name;) variables_.push_back(name);
  default_response_ = substituted(default_response_);
  std::istringstream text(data_.text(manager, "rules", ""));
  std::vector<std::string> words;
  for (std::string word; text >> word;) words.push_back(word);
  const auto word = [](const std::string& w) {
    Rule::Word parsed;
    if (!is_group_word(w)) {
      parsed.name = w;
      return parsed;
    }
    try {
      parsed.group = std::stoi(w);
    } catch (const std::exception&) {
      parsed.group = 0;  // SOFA: a number it cannot read is group 0
    }
    return parsed;
  };
  std::size_t i = 0;
  for (; i + 3 <= words.size(); i += 3) rules_.push_back({word(words[i]), word(words[i + 1]), substituted(words[i + 2])});
  if (i < words.size()) {
    std::string rest;
    for (; i < words.size(); ++i) rest += (rest.empty() ? "" : " ") + words[i];
    data_.warn(manager.where() + ": rules: '" + rest + "' is not a whole rule (model, model, response): ignored, as SOFA" +
               (rules_.empty() ? "; every pair gets the response " + default_response_ : ""));
  }
}

std::string ContactManagerRules::substituted(const std::string& response) const {
  std::string result;
  std::size_t next = 0;
  while (next < response.size()) {
    const std::size_t open = response.find('$', next);
    if (open == std::string::npos) {
      result += response.substr(next);
      break;
    }
    result += response.substr(next, open - next);
    const std::size_t close = response.find('$', open + 1);
    if (close == std::string::npos) {
      data_.warn(manager_.where() + ": the response '" + response + "' opens a $variable$ it does not close");
      result += response.substr(open);
      break;
    }
    const std::string name = response.substr(open + 1, close - open - 1);
    if (std::find(variables_.begin(), variables_.end(), name) == variables_.end()) {
      data_.warn(manager_.where() + ": the response '" + response + "' uses $" + name +
                 "$, which `variables` does not declare: replaced by nothing, as SOFA");
    } else {
      result += data_.text(manager_, name, "");
    }
    next = close + 1;
  }
  return result;
}

std::string ContactManagerRules::response(const ContactModelIdentity& model1, const ContactModelIdentity& model2) const {
  const std::string& own1 = model1.contact_response;
  const std::string& own2 = model2.contact_response;
  if (!rule_based_) {
    // SOFA's CollisionResponse::getContactResponse.
    if (own1.empty()) return own2.empty() ? default_response_ : own2;
    if (own2.empty() || own1 == own2) return own1;
    return default_response_;
  }
  if (!own1.empty()) return own1;
  if (!own2.empty()) return own2;
  for (const Rule& rule : rules_) {
    if ((rule.first.matches(model1) && rule.second.matches(model2)) || (rule.first.matches(model2) && rule.second.matches(model1))) {
      return rule.response;
    }
  }
  return default_response_;
}

}  // namespace fastcorot::scene_detail
