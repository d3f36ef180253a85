// Checks of derived metadata as a repository's ingest reads it, shared by the mapping tests on
// the sample carrier and on generated captures:
//   - PREMIS inside METS: every link (agent, event, object, rights statement) resolves within
//     the document, each agent and event is defined once, and every file a step made has a path
//     of derivation relationships and events back to the photographs;
//   - CIDOC-CRM: every class and property is one of tests/mapping/data/crm-terms.tsv and every
//     triple keeps its property's domain and range; time-spans of P9 parts nest; every result
//     has a chain of L11/L10 back to what the digitization made.
// Each returns the problems found, one line each (empty: none), so a test can print them all.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace archival {

// PREMIS objects, events and agents of a METS document, by their identifiers.
struct Premis {
  struct Link {
    std::string type, value, role;
  };
  struct Object {
    std::string kind;  // premis:file, premis:intellectualEntity
    std::vector<std::pair<std::string, std::string>> ids;  // (type, value)
    std::vector<Link> derivedFrom;  // derivation "has source": related objects
    std::vector<std::string> derivationEvents;  // relatedEventIdentifierValue of those
    std::vector<std::string> events;  // linkingEventIdentifierValue
    std::vector<std::string> rights;  // linkingRightsStatementIdentifierValue
    std::vector<Link> relatedObjects;  // every relatedObjectIdentifier
  };
  struct Event {
    std::string id, type, typeUri, dateTime, outcome;
    std::vector<Link> agents, objects;
  };
  struct Agent {
    std::string type, value, name, agentType;
  };
  std::vector<Object> objects;
  std::vector<Event> events;
  std::vector<Agent> agents;
  std::vector<std::string> rightsStatements;
  std::vector<std::pair<std::string, std::string>> files;  // (FLocat href, MIMETYPE) of fileSec
};

Premis readPremis(const std::string& metsXml);

// Problems with links and uniqueness.
std::vector<std::string> linkProblems(const Premis& p);
// For every object `derived` (payload paths): no path of "has source" relationships, each with
// its event, back to an object the capture event made.
std::vector<std::string> derivationProblems(const Premis& p, const std::vector<std::string>& derived);

// N-Triples (rapper -o ntriples) as (subject, predicate, object) with IRIs without <>, literals
// with their quotes.
struct Triple {
  std::string s, p, o;
  bool literal() const { return !o.empty() && o[0] == '"'; }
};
std::vector<Triple> parseNTriples(const std::string& text);
// RDF/XML text -> triples, through rapper (which must be installed).
std::vector<Triple> rdfTriples(const std::string& rdfXml, const std::string& scratchDir);

std::vector<std::string> crmTermProblems(const std::vector<Triple>& triples, const std::string& tablePath);
std::vector<std::string> timeSpanNestingProblems(const std::vector<Triple>& triples);
// Every node typed E36 (results) reaches, by L11 (made by) and L10 (used), a file that the
// D2 digitization output.
std::vector<std::string> crmDerivationProblems(const std::vector<Triple>& triples);

}  // namespace archival
