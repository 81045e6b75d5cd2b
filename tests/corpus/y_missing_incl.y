$YINCL no_such_file.y
$YDOIT
$YSTOP
