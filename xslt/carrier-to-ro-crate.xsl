<?xml version="1.0" encoding="UTF-8"?>
<!--
  Surrogate carrier -> RO-Crate 1.1 metadata (data/ro-crate-metadata.json), JSON-LD, following
  the Process Run Crate, Workflow Run Crate and Provenance Run Crate profiles 0.5.

  Input: a carrier (namespace urn:surrogate:carrier:1, schema xsd/carrier.xsd).
  The crate is the package's payload folder (data/): the capture. What it says:
    the root Dataset is the capture (title, description, creators, licence and rights, the
      packaging time as datePublished), with every file of the payload as a File: size,
      SHA-256, media type and PRONOM format (a WebSite entity per PUID, as RO-Crate 1.1 asks);
    the carrier (assembly-files/carrier.xml) is the crate's main entity, typed as a
      ComputationalWorkflow and HowTo: its process section is the plan Surrogate executes (and
      verify executes again when it re-executes), written in the carrier's own language;
    each recorded step is a HowToStep of that plan (its position, the stage that implements it
      as a SoftwareApplication with the stage version), its execution a CreateAction (the stage
      as instrument, what it read and its parameters as object, what it wrote as result, its
      times and status) and a ControlAction linking the two;
    the whole processing is a CreateAction of the carrier, and Surrogate's own execution an
      OrganizeAction (Surrogate and the libraries it recorded, their versions).
  Parameters (what the carrier cannot hold; from bag-info.txt and the payload):
    package-id      Surrogate-Package-Identifier
    packaging-time  Surrogate-Packaging-Time
    has-report      'true' when the payload holds finished-files/report.html
  File identifiers are the payload paths relative to data/, percent-encoded (EXSLT
  str:encode-uri and str:replace, which libxslt and xsltproc provide).
  The mapping is explained, element by element, in mappings/carrier-to-ro-crate.md.
  Re-derive by hand: xsltproc with the three string parameters above (its stringparam option),
    xslt/carrier-to-ro-crate.xsl, data/assembly-files/carrier.xml.
  Output is deterministic: the same carrier and parameters give the same bytes.
-->
<xsl:stylesheet version="1.0"
    xmlns:xsl="http://www.w3.org/1999/XSL/Transform"
    xmlns:c="urn:surrogate:carrier:1"
    xmlns:str="http://exslt.org/strings"
    extension-element-prefixes="str"
    exclude-result-prefixes="c str">

  <xsl:output method="text" encoding="UTF-8"/>
  <xsl:strip-space elements="*"/>

  <xsl:param name="package-id" select="''"/>
  <xsl:param name="packaging-time" select="''"/>
  <xsl:param name="has-report" select="''"/>
  <!-- The edition of these rules (src/mapping/mapping.h, kMappingEdition): 1 for packages made
       before the root always named a licence. -->
  <xsl:param name="mapping-edition" select="2"/>

  <xsl:variable name="carrier" select="/c:carrier"/>
  <xsl:variable name="carrier-path" select="'assembly-files/carrier.xml'"/>
  <xsl:variable name="report-path" select="'finished-files/report.html'"/>
  <xsl:variable name="nl" select="'&#10;'"/>

  <xsl:key name="file-by-id" match="c:files/c:file" use="@id"/>
  <xsl:key name="file-by-creator" match="c:files/c:file" use="@createdBy"/>
  <xsl:key name="result-by-step" match="c:data/c:result" use="@step"/>
  <!-- What a step read: the same keys and expression as carrier-to-crm.xsl's L10_had_input and
       carrier-to-mets.xsl's step-sources (mappings/carrier-to-crm.md says why each file). -->
  <xsl:key name="step-input" match="c:data/c:result/c:input/@file | c:data/c:result/*/@image" use="concat(../../@step, ' ', .)"/>
  <xsl:key name="decoded-image" match="c:data/c:result/c:decoded/@image" use="."/>
  <xsl:key name="stage" match="c:process/c:step" use="concat(@component, ' ', @version)"/>
  <xsl:key name="person" match="c:header/c:creator" use="normalize-space(.)"/>

  <!-- JSON text. EXSLT's str:replace in expressions, not recursive templates: in libxslt a
       template's text result is a result tree fragment, and fragments made in a loop over the
       files made the stylesheet quadratic (20 000 files: 11 s of CPU, 5000: 0.9 s). -->

  <!-- A JSON string: the text quoted, with \ " and the three control characters XML 1.0 text
       can hold (line feed, carriage return, tab) escaped (RFC 8259, section 7). -->
  <xsl:template name="json">
    <xsl:param name="s"/>
    <xsl:value-of select="concat('&quot;', str:replace(str:replace(str:replace(str:replace(str:replace(string($s), '\', '\\'), '&quot;', '\&quot;'), '&#10;', '\n'), '&#13;', '\r'), '&#9;', '\t'), '&quot;')"/>
  </xsl:template>

  <!-- ,"name": "value" on its own line (nothing when the value is empty) -->
  <xsl:template name="prop">
    <xsl:param name="name"/>
    <xsl:param name="value"/>
    <xsl:if test="string($value) != ''">
      <xsl:value-of select="concat(',', $nl, '      &quot;', $name, '&quot;: ')"/>
      <xsl:call-template name="json"><xsl:with-param name="s" select="$value"/></xsl:call-template>
    </xsl:if>
  </xsl:template>

  <!-- ,"name": {"@id": "value"} -->
  <xsl:template name="ref">
    <xsl:param name="name"/>
    <xsl:param name="id"/>
    <xsl:if test="string($id) != ''">
      <xsl:value-of select="concat(',', $nl, '      &quot;', $name, '&quot;: {&quot;@id&quot;: ')"/>
      <xsl:call-template name="json"><xsl:with-param name="s" select="$id"/></xsl:call-template>
      <xsl:text>}</xsl:text>
    </xsl:if>
  </xsl:template>

  <!-- {"@id": "..."} for a list item, with the separator before it unless first -->
  <xsl:template name="item">
    <xsl:param name="id"/>
    <xsl:param name="first"/>
    <xsl:if test="not($first)">,</xsl:if>
    <xsl:value-of select="concat($nl, '        {&quot;@id&quot;: ')"/>
    <xsl:call-template name="json"><xsl:with-param name="s" select="$id"/></xsl:call-template>
    <xsl:text>}</xsl:text>
  </xsl:template>

  <!-- Opens an entity: its @id and @type (a JSON array when it holds a comma) -->
  <xsl:template name="open">
    <xsl:param name="id"/>
    <xsl:param name="type"/>
    <xsl:param name="first" select="false()"/>
    <xsl:if test="not($first)">,</xsl:if>
    <xsl:value-of select="concat($nl, '    {', $nl, '      &quot;@id&quot;: ')"/>
    <xsl:call-template name="json"><xsl:with-param name="s" select="$id"/></xsl:call-template>
    <xsl:value-of select="concat(',', $nl, '      &quot;@type&quot;: ')"/>
    <xsl:choose>
      <xsl:when test="contains($type, ',')">
        <xsl:text>[</xsl:text>
        <xsl:call-template name="type-list"><xsl:with-param name="types" select="$type"/></xsl:call-template>
        <xsl:text>]</xsl:text>
      </xsl:when>
      <xsl:otherwise><xsl:call-template name="json"><xsl:with-param name="s" select="$type"/></xsl:call-template></xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <xsl:template name="type-list">
    <xsl:param name="types"/>
    <xsl:choose>
      <xsl:when test="contains($types, ',')">
        <xsl:call-template name="json"><xsl:with-param name="s" select="substring-before($types, ',')"/></xsl:call-template>
        <xsl:text>, </xsl:text>
        <xsl:call-template name="type-list"><xsl:with-param name="types" select="substring-after($types, ',')"/></xsl:call-template>
      </xsl:when>
      <xsl:otherwise><xsl:call-template name="json"><xsl:with-param name="s" select="$types"/></xsl:call-template></xsl:otherwise>
    </xsl:choose>
  </xsl:template>
  <xsl:template name="close"><xsl:value-of select="concat($nl, '    }')"/></xsl:template>
  <xsl:template name="list-open">
    <xsl:param name="name"/>
    <xsl:value-of select="concat(',', $nl, '      &quot;', $name, '&quot;: [')"/>
  </xsl:template>
  <xsl:template name="list-close"><xsl:value-of select="concat($nl, '      ]')"/></xsl:template>

  <!-- Identifiers -->
  <xsl:template name="person-id">
    <xsl:param name="name"/>
    <xsl:value-of select="concat('#person-', str:encode-uri(normalize-space($name), true()))"/>
  </xsl:template>
  <xsl:template name="stage-id">
    <xsl:param name="step"/>
    <xsl:value-of select="concat('#stage-', str:encode-uri($step/@component, true()), '-', str:encode-uri($step/@version, true()))"/>
  </xsl:template>
  <xsl:template name="software-id">
    <xsl:param name="software"/>
    <xsl:value-of select="concat('#software-', str:encode-uri($software/@name, true()))"/>
  </xsl:template>
  <xsl:variable name="pronom" select="'https://www.nationalarchives.gov.uk/PRONOM/'"/>

  <!-- Who ran the processing: the last recorded command's user, when known. -->
  <xsl:variable name="runner" select="normalize-space($carrier/c:header/c:run[last()]/@who)"/>
  <xsl:variable name="runner-id">
    <xsl:if test="$runner != '' and $runner != 'unknown'">
      <xsl:call-template name="person-id"><xsl:with-param name="name" select="$runner"/></xsl:call-template>
    </xsl:if>
  </xsl:variable>
  <xsl:variable name="ran" select="$carrier/c:process/c:step[key('result-by-step', @id)]"/>
  <xsl:variable name="first-start">
    <xsl:for-each select="$carrier/c:data/c:result/@started"><xsl:sort select="."/><xsl:if test="position() = 1"><xsl:value-of select="."/></xsl:if></xsl:for-each>
  </xsl:variable>
  <xsl:variable name="last-end">
    <xsl:for-each select="$carrier/c:data/c:result/@ended"><xsl:sort select="." order="descending"/><xsl:if test="position() = 1"><xsl:value-of select="."/></xsl:if></xsl:for-each>
  </xsl:variable>
  <xsl:variable name="license-id">
    <xsl:choose>
      <xsl:when test="normalize-space($carrier/c:header/c:license) != ''"><xsl:value-of select="normalize-space($carrier/c:header/c:license)"/></xsl:when>
      <xsl:when test="normalize-space($carrier/c:header/c:rights) != ''">#rights</xsl:when>
      <!-- RO-Crate 1.1 requires a licence on the root: one that says none was stated (from
           the mappings' edition 2; src/mapping/mapping.h, kMappingEdition). -->
      <xsl:when test="$mapping-edition &gt;= 2">#no-licence-stated</xsl:when>
    </xsl:choose>
  </xsl:variable>
  <xsl:variable name="surrogate" select="$carrier/c:header/c:software[@name = 'Surrogate'][1]"/>
  <xsl:variable name="capture-id">
    <xsl:choose>
      <xsl:when test="$carrier/c:files/c:file"><xsl:value-of select="concat('urn:surrogate:capture:', $carrier/c:files/c:file[1]/@sha256)"/></xsl:when>
      <xsl:otherwise>urn:surrogate:capture:unidentified</xsl:otherwise>
    </xsl:choose>
  </xsl:variable>

  <xsl:template match="/">
    <xsl:apply-templates select="c:carrier"/>
  </xsl:template>

  <xsl:template match="c:carrier">
    <xsl:text>{
  "@context": [
    "https://w3id.org/ro/crate/1.1/context",
    "https://w3id.org/ro/terms/workflow-run/context"
  ],
  "@graph": [</xsl:text>
    <xsl:call-template name="descriptor"/>
    <xsl:call-template name="root"/>
    <xsl:call-template name="profiles"/>
    <xsl:call-template name="workflow"/>
    <xsl:call-template name="software"/>
    <xsl:apply-templates select="c:process/c:step" mode="plan"/>
    <xsl:apply-templates select="$ran" mode="execution"/>
    <xsl:call-template name="processing"/>
    <xsl:call-template name="people"/>
    <xsl:apply-templates select="c:files/c:file"/>
    <xsl:if test="$has-report = 'true'">
      <xsl:call-template name="open"><xsl:with-param name="id" select="$report-path"/><xsl:with-param name="type" select="'File'"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="'report.html'"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'description'"/><xsl:with-param name="value" select="'The report: a view of the carrier for people, made when the capture was processed; not recorded in the carrier, which it shows.'"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'encodingFormat'"/><xsl:with-param name="value" select="'text/html'"/></xsl:call-template>
      <xsl:call-template name="ref"><xsl:with-param name="name" select="'about'"/><xsl:with-param name="id" select="'#processing'"/></xsl:call-template>
      <xsl:call-template name="close"/>
    </xsl:if>
    <xsl:call-template name="formats"/>
    <xsl:call-template name="licence"/>
    <xsl:value-of select="concat($nl, '  ]', $nl, '}', $nl)"/>
  </xsl:template>

  <xsl:template name="descriptor">
    <xsl:call-template name="open"><xsl:with-param name="id" select="'ro-crate-metadata.json'"/><xsl:with-param name="type" select="'CreativeWork'"/><xsl:with-param name="first" select="true()"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'about'"/><xsl:with-param name="id" select="'./'"/></xsl:call-template>
    <xsl:call-template name="list-open"><xsl:with-param name="name" select="'conformsTo'"/></xsl:call-template>
    <xsl:call-template name="item"><xsl:with-param name="id" select="'https://w3id.org/ro/crate/1.1'"/><xsl:with-param name="first" select="true()"/></xsl:call-template>
    <xsl:call-template name="item"><xsl:with-param name="id" select="'https://w3id.org/workflowhub/workflow-ro-crate/1.0'"/></xsl:call-template>
    <xsl:call-template name="list-close"/>
    <xsl:call-template name="close"/>
  </xsl:template>

  <xsl:template name="root">
    <xsl:variable name="h" select="$carrier/c:header"/>
    <xsl:call-template name="open"><xsl:with-param name="id" select="'./'"/><xsl:with-param name="type" select="'Dataset'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="normalize-space($h/c:title)"/></xsl:call-template>
    <xsl:call-template name="prop">
      <xsl:with-param name="name" select="'description'"/>
      <xsl:with-param name="value">
        <xsl:choose>
          <xsl:when test="$h/c:meta[@key = 'External-Description']"><xsl:value-of select="$h/c:meta[@key = 'External-Description'][1]"/></xsl:when>
          <xsl:otherwise><xsl:value-of select="concat('Highlight-RTI capture: ', normalize-space($h/c:title))"/></xsl:otherwise>
        </xsl:choose>
      </xsl:with-param>
    </xsl:call-template>
    <!-- The package's identifier, then the capture's (the same for every package of it:
         urn:surrogate:capture: and the SHA-256 of the carrier's first file, as in
         carrier-to-crm.xsl and bag-info.txt's Surrogate-Capture-Identifier). -->
    <xsl:value-of select="concat(',', $nl, '      &quot;identifier&quot;: [')"/>
    <xsl:if test="$package-id != ''">
      <xsl:call-template name="json"><xsl:with-param name="s" select="$package-id"/></xsl:call-template>
      <xsl:text>, </xsl:text>
    </xsl:if>
    <xsl:call-template name="json"><xsl:with-param name="s" select="$capture-id"/></xsl:call-template>
    <xsl:text>]</xsl:text>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'datePublished'"/><xsl:with-param name="value" select="$packaging-time"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'dateCreated'"/><xsl:with-param name="value" select="$h/c:created"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'dateModified'"/><xsl:with-param name="value" select="$h/c:modified"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'license'"/><xsl:with-param name="id" select="$license-id"/></xsl:call-template>
    <xsl:if test="$h/c:creator">
      <xsl:call-template name="list-open"><xsl:with-param name="name" select="'creator'"/></xsl:call-template>
      <xsl:for-each select="$h/c:creator[count(. | key('person', normalize-space(.))[1]) = 1]">
        <xsl:call-template name="item">
          <xsl:with-param name="id"><xsl:call-template name="person-id"><xsl:with-param name="name" select="."/></xsl:call-template></xsl:with-param>
          <xsl:with-param name="first" select="position() = 1"/>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="list-close"/>
    </xsl:if>
    <xsl:call-template name="list-open"><xsl:with-param name="name" select="'conformsTo'"/></xsl:call-template>
    <xsl:call-template name="item"><xsl:with-param name="id" select="'https://w3id.org/ro/wfrun/process/0.5'"/><xsl:with-param name="first" select="true()"/></xsl:call-template>
    <xsl:call-template name="item"><xsl:with-param name="id" select="'https://w3id.org/ro/wfrun/workflow/0.5'"/></xsl:call-template>
    <xsl:call-template name="item"><xsl:with-param name="id" select="'https://w3id.org/ro/wfrun/provenance/0.5'"/></xsl:call-template>
    <xsl:call-template name="item"><xsl:with-param name="id" select="'https://w3id.org/workflowhub/workflow-ro-crate/1.0'"/></xsl:call-template>
    <xsl:call-template name="list-close"/>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'mainEntity'"/><xsl:with-param name="id" select="$carrier-path"/></xsl:call-template>
    <xsl:call-template name="list-open"><xsl:with-param name="name" select="'hasPart'"/></xsl:call-template>
    <xsl:call-template name="item"><xsl:with-param name="id" select="$carrier-path"/><xsl:with-param name="first" select="true()"/></xsl:call-template>
    <xsl:for-each select="$carrier/c:files/c:file">
      <xsl:call-template name="item"><xsl:with-param name="id" select="str:replace(str:encode-uri(@path, true()), '%2F', '/')"/></xsl:call-template>
    </xsl:for-each>
    <xsl:if test="$has-report = 'true'">
      <xsl:call-template name="item"><xsl:with-param name="id" select="$report-path"/></xsl:call-template>
    </xsl:if>
    <xsl:call-template name="list-close"/>
    <xsl:call-template name="list-open"><xsl:with-param name="name" select="'mentions'"/></xsl:call-template>
    <xsl:call-template name="item"><xsl:with-param name="id" select="'#processing'"/><xsl:with-param name="first" select="true()"/></xsl:call-template>
    <xsl:call-template name="item"><xsl:with-param name="id" select="'#surrogate-execution'"/></xsl:call-template>
    <xsl:for-each select="$ran">
      <xsl:call-template name="item"><xsl:with-param name="id" select="concat('#execution-', @id)"/></xsl:call-template>
    </xsl:for-each>
    <xsl:call-template name="list-close"/>
    <xsl:call-template name="close"/>
  </xsl:template>

  <xsl:template name="profile">
    <xsl:param name="id"/>
    <xsl:param name="name"/>
    <xsl:param name="version"/>
    <xsl:call-template name="open"><xsl:with-param name="id" select="$id"/><xsl:with-param name="type" select="'CreativeWork'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="$name"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'version'"/><xsl:with-param name="value" select="$version"/></xsl:call-template>
    <xsl:call-template name="close"/>
  </xsl:template>
  <xsl:template name="profiles">
    <xsl:call-template name="profile"><xsl:with-param name="id" select="'https://w3id.org/ro/wfrun/process/0.5'"/><xsl:with-param name="name" select="'Process Run Crate'"/><xsl:with-param name="version" select="'0.5'"/></xsl:call-template>
    <xsl:call-template name="profile"><xsl:with-param name="id" select="'https://w3id.org/ro/wfrun/workflow/0.5'"/><xsl:with-param name="name" select="'Workflow Run Crate'"/><xsl:with-param name="version" select="'0.5'"/></xsl:call-template>
    <xsl:call-template name="profile"><xsl:with-param name="id" select="'https://w3id.org/ro/wfrun/provenance/0.5'"/><xsl:with-param name="name" select="'Provenance Run Crate'"/><xsl:with-param name="version" select="'0.5'"/></xsl:call-template>
    <xsl:call-template name="profile"><xsl:with-param name="id" select="'https://w3id.org/workflowhub/workflow-ro-crate/1.0'"/><xsl:with-param name="name" select="'Workflow RO-Crate'"/><xsl:with-param name="version" select="'1.0'"/></xsl:call-template>
  </xsl:template>

  <!-- The carrier as the workflow: its process section is the plan Surrogate runs. -->
  <xsl:template name="workflow">
    <xsl:call-template name="open"><xsl:with-param name="id" select="$carrier-path"/><xsl:with-param name="type" select="'File,SoftwareSourceCode,ComputationalWorkflow,HowTo'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="'carrier.xml'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'description'"/><xsl:with-param name="value" select="'The provenance record of the capture (the carrier): every file with its SHA-256, every processing step with its software version and parameters, every decision made by hand. Its process section is the plan Surrogate executes, and executes again to verify the results.'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'encodingFormat'"/><xsl:with-param name="value" select="'application/xml'"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'programmingLanguage'"/><xsl:with-param name="id" select="'#surrogate-carrier'"/></xsl:call-template>
    <xsl:if test="c:process/c:step | $carrier/c:process/c:step">
      <xsl:call-template name="list-open"><xsl:with-param name="name" select="'hasPart'"/></xsl:call-template>
      <xsl:for-each select="$carrier/c:process/c:step[count(. | key('stage', concat(@component, ' ', @version))[1]) = 1]">
        <xsl:call-template name="item">
          <xsl:with-param name="id"><xsl:call-template name="stage-id"><xsl:with-param name="step" select="."/></xsl:call-template></xsl:with-param>
          <xsl:with-param name="first" select="position() = 1"/>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="list-close"/>
      <xsl:call-template name="list-open"><xsl:with-param name="name" select="'step'"/></xsl:call-template>
      <xsl:for-each select="$carrier/c:process/c:step">
        <xsl:call-template name="item"><xsl:with-param name="id" select="concat('#step-', @id)"/><xsl:with-param name="first" select="position() = 1"/></xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="list-close"/>
    </xsl:if>
    <xsl:call-template name="close"/>
    <xsl:call-template name="open"><xsl:with-param name="id" select="'#surrogate-carrier'"/><xsl:with-param name="type" select="'ComputerLanguage'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="'Surrogate carrier'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'alternateName'"/><xsl:with-param name="value" select="'urn:surrogate:carrier:1'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'version'"/><xsl:with-param name="value" select="$carrier/@version"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'description'"/><xsl:with-param name="value" select="'The XML provenance document of Surrogate; schema in metadata/xsd/carrier.xsd, explained in metadata/docs/carrier.md (paths from the bag root).'"/></xsl:call-template>
    <xsl:call-template name="close"/>
  </xsl:template>

  <!-- Surrogate and the libraries it recorded; each stage that ran. -->
  <xsl:template name="software">
    <xsl:call-template name="open"><xsl:with-param name="id" select="'#surrogate'"/><xsl:with-param name="type" select="'SoftwareApplication'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="'Surrogate'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'softwareVersion'"/><xsl:with-param name="value" select="$surrogate/@version"/></xsl:call-template>
    <xsl:variable name="libraries" select="$carrier/c:header/c:software[@name != 'Surrogate']"/>
    <xsl:if test="$libraries">
      <xsl:call-template name="list-open"><xsl:with-param name="name" select="'softwareRequirements'"/></xsl:call-template>
      <xsl:for-each select="$libraries">
        <xsl:call-template name="item">
          <xsl:with-param name="id"><xsl:call-template name="software-id"><xsl:with-param name="software" select="."/></xsl:call-template></xsl:with-param>
          <xsl:with-param name="first" select="position() = 1"/>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="list-close"/>
    </xsl:if>
    <xsl:call-template name="close"/>
    <xsl:for-each select="$carrier/c:header/c:software[@name != 'Surrogate']">
      <xsl:call-template name="open">
        <xsl:with-param name="id"><xsl:call-template name="software-id"><xsl:with-param name="software" select="."/></xsl:call-template></xsl:with-param>
        <xsl:with-param name="type" select="'SoftwareApplication'"/>
      </xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="@name"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'softwareVersion'"/><xsl:with-param name="value" select="@version"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'description'"/><xsl:with-param name="value" select="@role"/></xsl:call-template>
      <xsl:call-template name="close"/>
    </xsl:for-each>
    <xsl:for-each select="$carrier/c:process/c:step[count(. | key('stage', concat(@component, ' ', @version))[1]) = 1]">
      <xsl:call-template name="open">
        <xsl:with-param name="id"><xsl:call-template name="stage-id"><xsl:with-param name="step" select="."/></xsl:call-template></xsl:with-param>
        <xsl:with-param name="type" select="'SoftwareApplication'"/>
      </xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="concat('Surrogate ', @component, ' stage')"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'softwareVersion'"/><xsl:with-param name="value" select="@version"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'description'"/><xsl:with-param name="value" select="normalize-space(c:description)"/></xsl:call-template>
      <xsl:call-template name="ref"><xsl:with-param name="name" select="'isPartOf'"/><xsl:with-param name="id" select="'#surrogate'"/></xsl:call-template>
      <xsl:call-template name="close"/>
    </xsl:for-each>
  </xsl:template>

  <!-- A step of the plan -->
  <xsl:template match="c:step" mode="plan">
    <xsl:call-template name="open"><xsl:with-param name="id" select="concat('#step-', @id)"/><xsl:with-param name="type" select="'HowToStep'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="concat(@id, ': ', @component)"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'position'"/><xsl:with-param name="value" select="string(position())"/></xsl:call-template>
    <xsl:call-template name="ref">
      <xsl:with-param name="name" select="'workExample'"/>
      <xsl:with-param name="id"><xsl:call-template name="stage-id"><xsl:with-param name="step" select="."/></xsl:call-template></xsl:with-param>
    </xsl:call-template>
    <xsl:call-template name="close"/>
  </xsl:template>

  <!-- A step's execution: what it read, its parameters, what it wrote -->
  <xsl:template match="c:step" mode="execution">
    <xsl:variable name="step" select="."/>
    <xsl:variable name="result" select="key('result-by-step', @id)"/>
    <xsl:variable name="explicit" select="boolean($result/c:input/@file or $result/*/@image)"/>
    <xsl:variable name="decodeIds" select="$carrier/c:process/c:step[@component = 'ImageDecode']/@id"/>
    <xsl:variable name="useDecoded" select="(not($explicit) or ($step/@component = 'ColourCorrection' and $result/c:value[@name = 'outcome']/@value = 'corrected')) and $step/@component != 'CaptureIngest' and $step/@component != 'ImageDecode' and $step/@component != 'DerivedMaps'"/>
    <xsl:variable name="lights" select="key('result-by-step', $step/preceding-sibling::c:step[@component = 'LightDirections' or @component = 'LightsFromFile']/@id)/c:output[@kind = 'lp']/@file[$step/@component = 'RtiFit']"/>
    <xsl:variable name="model" select="key('result-by-step', $step/preceding-sibling::c:step[@component = 'RtiFit'][c:param[@name = 'basis']/@value = $step/c:param[@name = 'model']/@value]/@id)/c:output/@file[$step/@component = 'DerivedMaps']"/>
    <xsl:variable name="sources" select="$carrier/c:files/c:file[
        key('step-input', concat($step/@id, ' ', @id))
        or ($useDecoded and key('decoded-image', @id)[../../@step = $decodeIds])
        or @id = $lights or @id = $model]"/>
    <xsl:variable name="outputs" select="key('file-by-id', $result/c:output/@file) | key('file-by-creator', @id)"/>
    <xsl:variable name="action" select="concat('#execution-', @id)"/>
    <!-- Colour from a chart: what a reuser judges the colours of the results by (the chart's
         edition, the model, the CIEDE2000 figures and the quality levels they reach), as
         PropertyValues of the execution's result (Workflow Run Crate: an output that is not a
         file). Other steps' values stay in the carrier. -->
    <xsl:variable name="figures" select="$result[c:value[@name = 'outcome']/@value = 'corrected'][$step/@component = 'ColourCorrection']/c:value[
        @name = 'referenceTitle' or @name = 'model' or starts-with(@name, 'deltaE2000') or @name = 'qualityLevel']"/>

    <xsl:call-template name="open"><xsl:with-param name="id" select="$action"/><xsl:with-param name="type" select="'CreateAction'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="concat('Execution of step ', @id, ': ', @component, ' ', @version)"/></xsl:call-template>
    <xsl:if test="c:intervention">
      <xsl:call-template name="prop">
        <xsl:with-param name="name" select="'description'"/>
        <xsl:with-param name="value">
          <xsl:text>Decided by hand: </xsl:text>
          <xsl:for-each select="c:intervention">
            <xsl:if test="position() != 1">; </xsl:if>
            <xsl:value-of select="concat(@kind, ' ', @target)"/>
            <xsl:if test="@value != ''"><xsl:value-of select="concat(' = ', @value)"/></xsl:if>
            <xsl:value-of select="concat(' (', @who, ', ', @time)"/>
            <xsl:if test="normalize-space(.) != ''"><xsl:value-of select="concat(': ', normalize-space(.))"/></xsl:if>
            <xsl:text>)</xsl:text>
          </xsl:for-each>
        </xsl:with-param>
      </xsl:call-template>
    </xsl:if>
    <xsl:call-template name="ref">
      <xsl:with-param name="name" select="'instrument'"/>
      <xsl:with-param name="id"><xsl:call-template name="stage-id"><xsl:with-param name="step" select="."/></xsl:call-template></xsl:with-param>
    </xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'agent'"/><xsl:with-param name="id" select="$runner-id"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'startTime'"/><xsl:with-param name="value" select="$result/@started"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'endTime'"/><xsl:with-param name="value" select="$result/@ended"/></xsl:call-template>
    <xsl:call-template name="ref">
      <xsl:with-param name="name" select="'actionStatus'"/>
      <xsl:with-param name="id">
        <xsl:choose>
          <xsl:when test="$result/@status = 'failed'">http://schema.org/FailedActionStatus</xsl:when>
          <xsl:otherwise>http://schema.org/CompletedActionStatus</xsl:otherwise>
        </xsl:choose>
      </xsl:with-param>
    </xsl:call-template>
    <xsl:if test="$sources or c:param">
      <xsl:call-template name="list-open"><xsl:with-param name="name" select="'object'"/></xsl:call-template>
      <xsl:for-each select="$sources">
        <xsl:call-template name="item">
          <xsl:with-param name="id" select="str:replace(str:encode-uri(@path, true()), '%2F', '/')"/>
          <xsl:with-param name="first" select="position() = 1"/>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:for-each select="c:param">
        <xsl:call-template name="item">
          <xsl:with-param name="id" select="concat($action, '-parameter-', position())"/>
          <xsl:with-param name="first" select="not($sources) and position() = 1"/>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="list-close"/>
    </xsl:if>
    <xsl:if test="$outputs or $figures">
      <xsl:call-template name="list-open"><xsl:with-param name="name" select="'result'"/></xsl:call-template>
      <xsl:for-each select="$outputs">
        <xsl:call-template name="item">
          <xsl:with-param name="id" select="str:replace(str:encode-uri(@path, true()), '%2F', '/')"/>
          <xsl:with-param name="first" select="position() = 1"/>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:for-each select="$figures">
        <xsl:call-template name="item">
          <xsl:with-param name="id" select="concat($action, '-figure-', position())"/>
          <xsl:with-param name="first" select="not($outputs) and position() = 1"/>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="list-close"/>
    </xsl:if>
    <xsl:call-template name="close"/>

    <xsl:for-each select="$figures">
      <xsl:call-template name="open"><xsl:with-param name="id" select="concat($action, '-figure-', position())"/><xsl:with-param name="type" select="'PropertyValue'"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="@name"/></xsl:call-template>
      <xsl:value-of select="concat(',', $nl, '      &quot;value&quot;: ')"/>
      <xsl:call-template name="json"><xsl:with-param name="s" select="@value"/></xsl:call-template>
      <xsl:if test="starts-with(@name, 'deltaE2000')">
        <xsl:call-template name="prop"><xsl:with-param name="name" select="'unitText'"/><xsl:with-param name="value" select="'CIEDE2000'"/></xsl:call-template>
      </xsl:if>
      <xsl:call-template name="close"/>
    </xsl:for-each>

    <xsl:for-each select="c:param">
      <xsl:call-template name="open"><xsl:with-param name="id" select="concat($action, '-parameter-', position())"/><xsl:with-param name="type" select="'PropertyValue'"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="@name"/></xsl:call-template>
      <xsl:value-of select="concat(',', $nl, '      &quot;value&quot;: ')"/>
      <xsl:call-template name="json"><xsl:with-param name="s" select="@value"/></xsl:call-template>
      <xsl:call-template name="close"/>
    </xsl:for-each>

    <xsl:call-template name="open"><xsl:with-param name="id" select="concat('#control-', @id)"/><xsl:with-param name="type" select="'ControlAction'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="concat('Orchestration of step ', @id)"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'instrument'"/><xsl:with-param name="id" select="concat('#step-', @id)"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'object'"/><xsl:with-param name="id" select="$action"/></xsl:call-template>
    <xsl:call-template name="close"/>
  </xsl:template>

  <!-- The processing as a whole (the workflow run) and Surrogate's execution of it -->
  <xsl:template name="processing">
    <xsl:variable name="inputs" select="$carrier/c:files/c:file[@role != 'assembly' and @role != 'result']"/>
    <xsl:variable name="made" select="$carrier/c:files/c:file[@role = 'assembly' or @role = 'result']"/>
    <xsl:call-template name="open"><xsl:with-param name="id" select="'#processing'"/><xsl:with-param name="type" select="'CreateAction'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="concat('Processing of ', normalize-space($carrier/c:header/c:title))"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'instrument'"/><xsl:with-param name="id" select="$carrier-path"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'agent'"/><xsl:with-param name="id" select="$runner-id"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'startTime'"/><xsl:with-param name="value" select="$first-start"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'endTime'"/><xsl:with-param name="value" select="$last-end"/></xsl:call-template>
    <xsl:call-template name="ref">
      <xsl:with-param name="name" select="'actionStatus'"/>
      <xsl:with-param name="id">
        <xsl:choose>
          <xsl:when test="$carrier/c:data/c:result[@status = 'failed'] or count($ran) != count($carrier/c:process/c:step)">http://schema.org/FailedActionStatus</xsl:when>
          <xsl:otherwise>http://schema.org/CompletedActionStatus</xsl:otherwise>
        </xsl:choose>
      </xsl:with-param>
    </xsl:call-template>
    <xsl:if test="$inputs">
      <xsl:call-template name="list-open"><xsl:with-param name="name" select="'object'"/></xsl:call-template>
      <xsl:for-each select="$inputs">
        <xsl:call-template name="item">
          <xsl:with-param name="id" select="str:replace(str:encode-uri(@path, true()), '%2F', '/')"/>
          <xsl:with-param name="first" select="position() = 1"/>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="list-close"/>
    </xsl:if>
    <xsl:if test="$made">
      <xsl:call-template name="list-open"><xsl:with-param name="name" select="'result'"/></xsl:call-template>
      <xsl:for-each select="$made">
        <xsl:call-template name="item">
          <xsl:with-param name="id" select="str:replace(str:encode-uri(@path, true()), '%2F', '/')"/>
          <xsl:with-param name="first" select="position() = 1"/>
        </xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="list-close"/>
    </xsl:if>
    <xsl:call-template name="close"/>

    <xsl:call-template name="open"><xsl:with-param name="id" select="'#surrogate-execution'"/><xsl:with-param name="type" select="'OrganizeAction'"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="concat('Run of Surrogate ', $surrogate/@version)"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'instrument'"/><xsl:with-param name="id" select="'#surrogate'"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'agent'"/><xsl:with-param name="id" select="$runner-id"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'startTime'"/><xsl:with-param name="value" select="$first-start"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'endTime'"/><xsl:with-param name="value" select="$last-end"/></xsl:call-template>
    <xsl:call-template name="ref"><xsl:with-param name="name" select="'result'"/><xsl:with-param name="id" select="'#processing'"/></xsl:call-template>
    <xsl:if test="$ran">
      <xsl:call-template name="list-open"><xsl:with-param name="name" select="'object'"/></xsl:call-template>
      <xsl:for-each select="$ran">
        <xsl:call-template name="item"><xsl:with-param name="id" select="concat('#control-', @id)"/><xsl:with-param name="first" select="position() = 1"/></xsl:call-template>
      </xsl:for-each>
      <xsl:call-template name="list-close"/>
    </xsl:if>
    <xsl:call-template name="close"/>
  </xsl:template>

  <!-- The creators, and who ran the processing when known -->
  <xsl:template name="people">
    <xsl:for-each select="$carrier/c:header/c:creator[count(. | key('person', normalize-space(.))[1]) = 1]">
      <xsl:call-template name="open">
        <xsl:with-param name="id"><xsl:call-template name="person-id"><xsl:with-param name="name" select="."/></xsl:call-template></xsl:with-param>
        <xsl:with-param name="type" select="'Person'"/>
      </xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="normalize-space(.)"/></xsl:call-template>
      <xsl:call-template name="prop">
        <xsl:with-param name="name" select="'description'"/>
        <xsl:with-param name="value">
          <xsl:for-each select="key('person', normalize-space(.))/@role">
            <xsl:if test="position() != 1">, </xsl:if>
            <xsl:value-of select="."/>
          </xsl:for-each>
        </xsl:with-param>
      </xsl:call-template>
      <xsl:call-template name="close"/>
    </xsl:for-each>
    <xsl:if test="$runner-id != '' and not(key('person', $runner))">
      <xsl:call-template name="open"><xsl:with-param name="id" select="$runner-id"/><xsl:with-param name="type" select="'Person'"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="$runner"/></xsl:call-template>
      <xsl:call-template name="close"/>
    </xsl:if>
  </xsl:template>

  <!-- A file of the payload -->
  <xsl:template match="c:file">
    <xsl:call-template name="open">
      <xsl:with-param name="id" select="str:replace(str:encode-uri(@path, true()), '%2F', '/')"/>
      <xsl:with-param name="type" select="'File'"/>
    </xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="str:tokenize(@path, '/')[last()]"/></xsl:call-template>
    <xsl:if test="translate(@path, '%#?', '') != @path or contains(@path, ' ')">
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'alternateName'"/><xsl:with-param name="value" select="@path"/></xsl:call-template>
    </xsl:if>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'description'"/><xsl:with-param name="value" select="concat(@role, ' (', @format, ')')"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'contentSize'"/><xsl:with-param name="value" select="@size"/></xsl:call-template>
    <xsl:call-template name="prop"><xsl:with-param name="name" select="'sha256'"/><xsl:with-param name="value" select="@sha256"/></xsl:call-template>
    <xsl:choose>
      <xsl:when test="@puid != ''">
        <xsl:call-template name="list-open"><xsl:with-param name="name" select="'encodingFormat'"/></xsl:call-template>
        <xsl:if test="@mediaType != ''">
          <xsl:value-of select="concat($nl, '        ')"/>
          <xsl:call-template name="json"><xsl:with-param name="s" select="@mediaType"/></xsl:call-template>
          <xsl:text>,</xsl:text>
        </xsl:if>
        <xsl:call-template name="item"><xsl:with-param name="id" select="concat($pronom, @puid)"/><xsl:with-param name="first" select="true()"/></xsl:call-template>
        <xsl:call-template name="list-close"/>
      </xsl:when>
      <xsl:otherwise>
        <xsl:call-template name="prop"><xsl:with-param name="name" select="'encodingFormat'"/><xsl:with-param name="value" select="@mediaType"/></xsl:call-template>
      </xsl:otherwise>
    </xsl:choose>
    <xsl:if test="@createdBy != ''">
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'dateCreated'"/><xsl:with-param name="value" select="key('result-by-step', @createdBy)/@ended"/></xsl:call-template>
    </xsl:if>
    <xsl:call-template name="close"/>
  </xsl:template>


  <!-- Each PRONOM format named, as RO-Crate 1.1 describes a file format, in the order of their
       first files. One pass over the files per format: the usual grouping by key() copies the
       key's whole node-set for every file in libxslt, quadratic when most files share a PUID
       (20 000 files: 300 s). -->
  <xsl:template name="formats">
    <xsl:param name="seen" select="'|'"/>
    <xsl:variable name="next" select="($carrier/c:files/c:file[@puid != ''][not(contains($seen, concat('|', @puid, '|')))])[1]"/>
    <xsl:if test="$next">
      <xsl:call-template name="open"><xsl:with-param name="id" select="concat($pronom, $next/@puid)"/><xsl:with-param name="type" select="'WebSite'"/></xsl:call-template>
      <xsl:call-template name="prop"><xsl:with-param name="name" select="'name'"/><xsl:with-param name="value" select="concat('PRONOM ', $next/@puid, ': ', $next/@format)"/></xsl:call-template>
      <xsl:call-template name="close"/>
      <xsl:call-template name="formats"><xsl:with-param name="seen" select="concat($seen, $next/@puid, '|')"/></xsl:call-template>
    </xsl:if>
  </xsl:template>

  <xsl:template name="licence">
    <xsl:variable name="rights" select="normalize-space($carrier/c:header/c:rights)"/>
    <xsl:if test="$license-id != ''">
      <xsl:call-template name="open"><xsl:with-param name="id" select="$license-id"/><xsl:with-param name="type" select="'CreativeWork'"/></xsl:call-template>
      <xsl:call-template name="prop">
        <xsl:with-param name="name" select="'name'"/>
        <xsl:with-param name="value">
          <xsl:choose>
            <xsl:when test="$license-id = '#rights'">Rights statement</xsl:when>
            <xsl:when test="$license-id = '#no-licence-stated'">No licence stated</xsl:when>
            <xsl:otherwise><xsl:value-of select="$license-id"/></xsl:otherwise>
          </xsl:choose>
        </xsl:with-param>
      </xsl:call-template>
      <xsl:call-template name="prop">
        <xsl:with-param name="name" select="'description'"/>
        <xsl:with-param name="value">
          <xsl:choose>
            <xsl:when test="$license-id = '#no-licence-stated'">No licence or rights statement was recorded with the capture (surrogate run, options --license and --rights): the terms of use are not stated here; ask the depositor.</xsl:when>
            <xsl:otherwise><xsl:value-of select="$rights"/></xsl:otherwise>
          </xsl:choose>
        </xsl:with-param>
      </xsl:call-template>
      <xsl:call-template name="close"/>
    </xsl:if>
  </xsl:template>

</xsl:stylesheet>
