// placeholder: filled by the chart_detection work
