// Private to src/mapping: a transformation's result written out while it is being built, and
// freed as it is written, in exactly the bytes xsltSaveResultTo writes for the whole tree.
//
// libxslt builds the whole result tree before anything can be serialised; for a package of
// 100 000 files the METS tree alone takes about 2 GB. The output of XSLT 1.0 only grows at its
// end: every node that is not on the path of last children from the document down (the open
// elements) is finished and never changes again. libxslt calls its debugger hook before every
// instruction of a transformation whose context has debugging switched on; at those calls the
// finished nodes are serialised with libxml2's own serialiser (xmlNodeDumpOutput, as
// xsltSaveResultTo does) and freed. Only the start and end tags of the open elements and the
// indentation around them are written here, by the rules of libxml2's serialiser:
//
//   <a>            an element is indented (indent="yes") unless its parent has a text child;
//     <b/>         once a child of an open element has been written, that decision is made
//   </a>           for good, and a text child arriving later would change it after the fact.
//
// Such an element (element children first, then text: the bundled stylesheets never make one)
// is detected, and the stream then reports that it is not the document (diverged()): the
// caller derives again without streaming. Nothing else can make the bytes differ.
//
//   ResultStream stream(style, out);          // out: where the bytes go
//   stream.attach(ctxt);                      // before xsltApplyStylesheetUser(..., ctxt)
//   result = xsltApplyStylesheetUser(...);
//   stream.finish(result);                    // the rest; false if diverged()
#pragma once

#include <libxml/tree.h>
#include <libxml/xmlIO.h>
#include <libxslt/xsltInternals.h>

#include <string>
#include <vector>

namespace surrogate::mapping {

class ResultStream {
 public:
  // `out` stays the caller's (closed by the caller). A stylesheet whose output is not plain
  // XML (method html, xhtml or text, or a DOCTYPE) is not streamed: finish() writes it whole.
  ResultStream(xsltStylesheetPtr style, xmlOutputBufferPtr out);
  ~ResultStream();
  ResultStream(const ResultStream&) = delete;
  ResultStream& operator=(const ResultStream&) = delete;

  // Switches libxslt's debugger hook on for this context only (the global debugger state is
  // left alone, so other transformations in the process are not slowed down).
  void attach(xsltTransformContextPtr ctxt);

  // Writes what is left of `result` (the whole of it when nothing was streamed) and frees
  // the nodes written. Returns false when the bytes written are not xsltSaveResultTo's.
  bool finish(xmlDocPtr result);

  bool diverged() const { return diverged_; }

 private:
  struct Open {
    xmlNodePtr node;
    int level;
    bool format;  // whether its children are indented
    xmlAttrPtr lastAttribute;
    xmlNsPtr lastNamespace;
  };
  static void onInstruction(xmlNodePtr, xmlNodePtr, xsltTemplatePtr, xsltTransformContextPtr ctxt);
  void step(xsltTransformContextPtr ctxt);
  void flush(xmlDocPtr doc, bool final);
  void flushChildren(xmlNodePtr parent, std::size_t depth, bool final);
  bool needsCommit(xmlNodePtr element) const;
  void commit(xmlNodePtr element, std::size_t depth);
  void close(std::size_t depth);
  void dumpWhole(xmlNodePtr node, std::size_t depth);
  void afterChild(xmlNodePtr node, std::size_t depth);
  void indent(int level);
  void writeDeclaration(xmlDocPtr doc);
  int childLevel(std::size_t depth) const;
  bool childFormat(std::size_t depth) const;

  xsltStylesheetPtr style_;
  xmlOutputBufferPtr out_;
  xsltTransformContextPtr ctxt_ = nullptr;
  xmlDocPtr result_ = nullptr;
  const char* encoding_ = nullptr;
  bool indent_ = false, streamable_ = true, declared_ = false, diverged_ = false;
  unsigned calls_ = 0;
  std::vector<Open> open_;  // written start tags, from the root element down
};

}  // namespace surrogate::mapping
