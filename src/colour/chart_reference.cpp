// placeholder: filled by the chart_reference work
