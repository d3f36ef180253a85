#include "mapping/result_stream.h"

#include <libxml/globals.h>
#include <libxslt/imports.h>
#include <libxslt/xsltutils.h>

#include <cstring>
#include <mutex>

namespace surrogate::mapping {

namespace {

// libxml2's serialiser indents with at most this many characters (MAX_INDENT in xmlsave.c).
constexpr int kMaxIndent = 60;

// Libxslt calls the hook before every instruction: a flush every this many calls keeps what is
// held to a few finished nodes, and lets most nodes be written whole by libxml2.
constexpr unsigned kCallsPerFlush = 256;

thread_local ResultStream* currentStream = nullptr;

bool textLike(const xmlNode* node) {
  return node->type == XML_TEXT_NODE || node->type == XML_CDATA_SECTION_NODE ||
         node->type == XML_ENTITY_REF_NODE;
}

xmlAttrPtr lastAttribute(const xmlNode* node) {
  xmlAttrPtr a = node->properties;
  while (a && a->next) a = a->next;
  return a;
}

xmlNsPtr lastNamespace(const xmlNode* node) {
  xmlNsPtr n = node->nsDef;
  while (n && n->next) n = n->next;
  return n;
}

std::string qualifiedName(const xmlNode* node) {
  std::string name;
  if (node->ns && node->ns->prefix) name = std::string(reinterpret_cast<const char*>(node->ns->prefix)) + ":";
  return name + reinterpret_cast<const char*>(node->name);
}

int appendTo(void* context, const char* data, int length) {
  static_cast<std::string*>(context)->append(data, static_cast<std::size_t>(length));
  return length;
}

}  // namespace

ResultStream::ResultStream(xsltStylesheetPtr style, xmlOutputBufferPtr out) : style_(style), out_(out) {
  const xmlChar *method = nullptr, *encoding = nullptr, *doctypePublic = nullptr,
                *doctypeSystem = nullptr;
  int indent = 0;
  XSLT_GET_IMPORT_PTR(method, style, method)
  XSLT_GET_IMPORT_PTR(encoding, style, encoding)
  XSLT_GET_IMPORT_PTR(doctypePublic, style, doctypePublic)
  XSLT_GET_IMPORT_PTR(doctypeSystem, style, doctypeSystem)
  XSLT_GET_IMPORT_INT(indent, style, indent)
  indent_ = indent == 1;
  encoding_ = reinterpret_cast<const char*>(encoding);
  // Only method="xml" given explicitly: without a method, libxslt may turn the result into
  // HTML when its root is <html>.
  streamable_ = !style->methodURI && method && xmlStrEqual(method, BAD_CAST "xml") &&
                !doctypePublic && !doctypeSystem;
}

ResultStream::~ResultStream() {
  if (currentStream == this) currentStream = nullptr;
}

void ResultStream::attach(xsltTransformContextPtr ctxt) {
  static std::once_flag once;
  std::call_once(once, [] {
    // handler, add (none: no call stack is kept), drop
    static void* callbacks[3] = {reinterpret_cast<void*>(&ResultStream::onInstruction), nullptr, nullptr};
    xsltSetDebuggerCallbacks(3, callbacks);
  });
  ctxt_ = ctxt;
  if (!streamable_) return;
  // Any state but NONE, RUN_RESTART and QUIT runs the transformation as usual and calls the
  // hook. Documents loaded with document() are then not given document order up front
  // (mapping.cpp's loader does it).
  ctxt->debugStatus = XSLT_DEBUG_RUN;
  currentStream = this;
}

void ResultStream::onInstruction(xmlNodePtr, xmlNodePtr, xsltTemplatePtr, xsltTransformContextPtr ctxt) {
  ResultStream* s = currentStream;
  if (s && s->ctxt_ == ctxt) s->step(ctxt);
}

void ResultStream::step(xsltTransformContextPtr ctxt) {
  if (diverged_ || ++calls_ % kCallsPerFlush != 0) return;
  if (!result_) {
    // The result document, not a result tree fragment (a variable's value being built).
    xmlDocPtr doc = ctxt->output;
    if (!doc || doc->type != XML_DOCUMENT_NODE || XSLT_IS_RES_TREE_FRAG(doc)) return;
    result_ = doc;
  }
  try {
    flush(result_, false);
  } catch (...) {
    diverged_ = true;  // never across libxslt; the caller derives again
  }
  // libxslt appends text to the last text node it made when that is still the insertion
  // point's last child: freed nodes must not be taken for it.
  ctxt->lasttext = nullptr;
  ctxt->lasttsize = ctxt->lasttuse = 0;
}

bool ResultStream::finish(xmlDocPtr result) {
  if (currentStream == this) currentStream = nullptr;
  if (!result) return !diverged_;
  if (!streamable_) {
    if (xsltSaveResultTo(out_, result, style_) < 0) diverged_ = true;
    return !diverged_;
  }
  if (diverged_ || (result_ && result_ != result)) return false;
  if (result->children) {
    flush(result, true);
    if (indent_) xmlOutputBufferWrite(out_, 1, "\n");
  }
  xmlOutputBufferFlush(out_);
  return !diverged_;
}

// The XML declaration as xsltSaveResultTo writes it, which also settles the encoding named to
// the serialiser.
void ResultStream::writeDeclaration(xmlDocPtr doc) {
  if (declared_) return;
  declared_ = true;
  int omit = 0, standalone = -1;
  XSLT_GET_IMPORT_INT(omit, style_, omitXmlDeclaration)
  XSLT_GET_IMPORT_INT(standalone, style_, standalone)
  if (omit == 1) return;
  xmlOutputBufferWriteString(out_, "<?xml version=");
  if (doc->version) {
    xmlOutputBufferWriteString(out_, "\"");
    xmlOutputBufferWriteString(out_, reinterpret_cast<const char*>(doc->version));
    xmlOutputBufferWriteString(out_, "\"");
  } else {
    xmlOutputBufferWriteString(out_, "\"1.0\"");
  }
  if (!encoding_) {
    if (doc->encoding) encoding_ = reinterpret_cast<const char*>(doc->encoding);
    else if (doc->charset != XML_CHAR_ENCODING_UTF8)
      encoding_ = xmlGetCharEncodingName(static_cast<xmlCharEncoding>(doc->charset));
  }
  if (encoding_) {
    xmlOutputBufferWriteString(out_, " encoding=\"");
    xmlOutputBufferWriteString(out_, encoding_);
    xmlOutputBufferWriteString(out_, "\"");
  }
  if (standalone == 0) xmlOutputBufferWriteString(out_, " standalone=\"no\"");
  if (standalone == 1) xmlOutputBufferWriteString(out_, " standalone=\"yes\"");
  xmlOutputBufferWriteString(out_, "?>\n");
}

void ResultStream::flush(xmlDocPtr doc, bool final) {
  flushChildren(reinterpret_cast<xmlNodePtr>(doc), 0, final);
}

// The level and indentation of the children of the node at `depth` (0: the document's,
// n: those of open_[n - 1]).
int ResultStream::childLevel(std::size_t depth) const { return depth == 0 ? 0 : open_[depth - 1].level + 1; }
bool ResultStream::childFormat(std::size_t depth) const { return depth == 0 ? indent_ : open_[depth - 1].format; }

// Whether an open element has finished children to write, itself or below its last child.
bool ResultStream::needsCommit(xmlNodePtr element) const {
  for (xmlNodePtr e = element; e && e->type == XML_ELEMENT_NODE && e->children; e = e->last)
    if (e->children != e->last) return true;
  return false;
}

// Writes the finished children of `parent` (all of them when `final`), and frees them.
void ResultStream::flushChildren(xmlNodePtr parent, std::size_t depth, bool final) {
  for (xmlNodePtr c = parent->children, next; c && !diverged_; c = next) {
    next = c->next;
    const bool committed = depth < open_.size() && open_[depth].node == c;
    if (!next && !final) {  // on the open path
      if (c->type != XML_ELEMENT_NODE) return;
      if (!committed && !needsCommit(c)) return;
      if (!committed) commit(c, depth);
      flushChildren(c, depth + 1, false);
      return;
    }
    if (committed) {
      flushChildren(c, depth + 1, true);
      close(depth);
    } else {
      dumpWhole(c, depth);
    }
    afterChild(c, depth);
    xmlUnlinkNode(c);
    xmlFreeNode(c);
  }
}

void ResultStream::indent(int level) {
  if (!xmlIndentTreeOutput || !xmlTreeIndentString) return;
  const int size = static_cast<int>(std::strlen(xmlTreeIndentString));
  if (size == 0) return;
  const int most = kMaxIndent / size;
  for (int i = 0; i < (level > most ? most : level); ++i) xmlOutputBufferWrite(out_, size, xmlTreeIndentString);
}

// An open element's start tag, written by libxml2 (attributes escaped as it escapes them):
// the element is serialised with one empty text child in place of its children, which also
// keeps the serialiser from indenting, and its end tag is cut off.
void ResultStream::commit(xmlNodePtr element, std::size_t depth) {
  writeDeclaration(element->doc);
  const int level = childLevel(depth);
  const bool parentFormat = childFormat(depth);
  if (depth > 0 && parentFormat) indent(level);
  bool format = parentFormat;
  for (xmlNodePtr c = element->children; c; c = c->next) format = format && !textLike(c);

  std::string tag;
  xmlOutputBufferPtr buffer = xmlOutputBufferCreateIO(appendTo, nullptr, &tag, nullptr);
  xmlNodePtr empty = xmlNewDocText(element->doc, BAD_CAST "");
  if (!buffer || !empty) {
    if (buffer) xmlOutputBufferClose(buffer);
    if (empty) xmlFreeNode(empty);
    diverged_ = true;
    return;
  }
  xmlNodePtr first = element->children, last = element->last;
  empty->parent = element;
  element->children = element->last = empty;
  xmlNodeDumpOutput(buffer, element->doc, element, level, 0, encoding_);
  xmlOutputBufferClose(buffer);
  element->children = first;
  element->last = last;
  xmlFreeNode(empty);
  const std::string end = "</" + qualifiedName(element) + ">";
  if (tag.size() < end.size() || tag.compare(tag.size() - end.size(), end.size(), end) != 0) {
    diverged_ = true;
    return;
  }
  xmlOutputBufferWrite(out_, static_cast<int>(tag.size() - end.size()), tag.data());
  if (format) xmlOutputBufferWrite(out_, 1, "\n");
  open_.push_back({element, level, format, lastAttribute(element), lastNamespace(element)});
}

// The end tag of open_[depth], once its children are written.
void ResultStream::close(std::size_t depth) {
  const Open o = open_[depth];
  // Attributes or namespaces added after the start tag was written (libxslt refuses
  // attributes after children; namespaces go on the element being made).
  if (depth + 1 != open_.size() || lastAttribute(o.node) != o.lastAttribute ||
      lastNamespace(o.node) != o.lastNamespace) {
    diverged_ = true;
    return;
  }
  if (o.format) indent(o.level);
  const std::string end = "</" + qualifiedName(o.node) + ">";
  xmlOutputBufferWrite(out_, static_cast<int>(end.size()), end.data());
  open_.pop_back();
}

// A finished node, by libxml2's serialiser as xsltSaveResultTo calls it for the whole tree
// (the indentation before it is the parent's).
void ResultStream::dumpWhole(xmlNodePtr node, std::size_t depth) {
  writeDeclaration(node->doc);
  const bool format = childFormat(depth);
  if (depth > 0 && format) {
    if (textLike(node)) {
      diverged_ = true;  // text under an element whose children were written indented
      return;
    }
    if (node->type == XML_ELEMENT_NODE || node->type == XML_PI_NODE || node->type == XML_COMMENT_NODE)
      indent(childLevel(depth));
  }
  xmlNodeDumpOutput(out_, node->doc, node, childLevel(depth), format ? 1 : 0, encoding_);
}

// What follows a child: a line break when its parent's children are indented (for the
// document's own children, after a DTD or a comment that is not last, as xsltSaveResultTo).
void ResultStream::afterChild(xmlNodePtr node, std::size_t depth) {
  if (depth == 0) {
    if (indent_ && (node->type == XML_DTD_NODE || (node->type == XML_COMMENT_NODE && node->next)))
      xmlOutputBufferWrite(out_, 1, "\n");
    return;
  }
  if (childFormat(depth) && node->type != XML_XINCLUDE_START && node->type != XML_XINCLUDE_END)
    xmlOutputBufferWrite(out_, 1, "\n");
}

}  // namespace surrogate::mapping
