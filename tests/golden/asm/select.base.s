; inputs finite with |x| <= 65536 (other batches run the general code)
; 4 points per iteration (xmm registers)
L0:
     0    push rbx
     1    push rbp
     2    push r12
     4    push r13
     6    push r14
     8    push r15
     a    sub rsp, 504
    11    mov rbx, rdi
    14    mov r12, rsi
    17    mov r15, r8
    1a    lea r13, [rdx+rdx*2]
    1e    add r13, rdx
    21    lea r14, [rcx+rcx*2]
    25    add r14, rcx
L2:
    28    cmp r13, r14
    2b    jae L3
L4:
    31    mov rax, [rbx]
    34    movups xmm2, [rax+r13*1]
    39    mov rax, [rbx+8]
    3d    movups xmm3, [rax+r13*1]
    42    movaps xmm4, [rip+L6]
    49    cmpltps xmm4, xmm2
    4d    andps xmm4, [rip+L7]
    54    mulps xmm2, [rip+L8]
    5b    xorps xmm3, [rip+L9]
    62    movaps xmm0, xmm4
    65    cmpneqps xmm0, [rip+L6]
    6d    movaps xmm5, xmm3
    70    blendvps xmm5, xmm2
    75    mov rax, [r12]
    79    movups [rax+r13*1], xmm5
L5:
    7e    add r13, 16
    82    jmp L2
L3:
    87    mov rax, 0x0
L1:
    8c    add rsp, 504
    93    pop r15
    95    pop r14
    97    pop r13
    99    pop r12
    9b    pop rbp
    9c    pop rbx
    9d    ret
L6:
    a0    .float 0, 0, 0, 0
L7:
    b0    .float 1, 1, 1, 1
L8:
    c0    .float 2, 2, 2, 2
L9:
    d0    .float -0, -0, -0, -0
